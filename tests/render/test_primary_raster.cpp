// Primary visibility by rasterisation (primary_raster.h): the triangle test on its own, and the
// G-buffer it gives against the one a traced ray per pixel gives, on scenes that try its edges:
// slivers and many small triangles, sphere lights, cut-outs, a camera inside a real level, and
// geometry closer to the eye than the raster's near plane.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "bounce/render/gbuffer.h"
#include "bounce/render/primary_raster.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

Ray ray_from(vec3 origin, vec3 direction) {
  Ray r;
  r.origin = origin;
  r.direction = glm::normalize(direction);
  r.tmin = 0.0f;
  return r;
}

TEST(IntersectTriangle, HitsAtTheAnalyticDistanceAndWeights) {
  // The triangle (0,0,2) (1,0,2) (0,1,2); a ray from the origin towards (0.25, 0.5, 2).
  const vec3 p0(0, 0, 2), p1(1, 0, 2), p2(0, 1, 2);
  float t = 0.0f;
  vec2 b(0.0f);
  ASSERT_TRUE(intersect_triangle(p0, p1, p2, ray_from(vec3(0.0f), vec3(0.25f, 0.5f, 2.0f)), t, b));
  EXPECT_NEAR(t, std::sqrt(0.25f * 0.25f + 0.25f + 4.0f), 1e-5f);
  EXPECT_NEAR(b.x, 0.25f, 1e-6f);
  EXPECT_NEAR(b.y, 0.5f, 1e-6f);
  // Outside an edge, behind the origin, beyond tmax: no hit.
  EXPECT_FALSE(intersect_triangle(p0, p1, p2, ray_from(vec3(0.0f), vec3(0.6f, 0.6f, 2.0f)), t, b));
  EXPECT_FALSE(intersect_triangle(p0, p1, p2, ray_from(vec3(0.0f), vec3(0.2f, 0.2f, -2.0f)), t, b));
  Ray short_ray = ray_from(vec3(0.0f), vec3(0.2f, 0.2f, 2.0f));
  short_ray.tmax = 1.0f;
  EXPECT_FALSE(intersect_triangle(p0, p1, p2, short_ray, t, b));
}

struct Compared {
  size_t pixels = 0, hits = 0, same = 0, candidates = 0;
  double worst_position = 0.0;  // relative to the distance, where the same triangle is hit
};

// The G-buffer of `scene` at w x h with the raster and with a traced ray per pixel.
Compared compare_with_rays(const Scene& scene, int w, int h, vec2 subpixel = vec2(0.3f, 0.7f)) {
  const SceneData data = SceneData::from(scene);
  const std::unique_ptr<Tracer> tracer = make_embree_tracer(scene);
  const CameraRays camera = CameraRays::from(scene.camera, w, h);
  PrimaryRaster raster;
  EXPECT_TRUE(raster.build(data.view(), camera, subpixel, w, h));
  GBuffer traced, rastered;
  traced.resize(w, h);
  rastered.resize(w, h);
  build_gbuffer(data.view(), *tracer, camera, subpixel, traced);
  build_gbuffer(data.view(), *tracer, camera, subpixel, rastered, &raster);
  Compared c;
  c.pixels = traced.size();
  for (size_t i = 0; i < c.pixels; ++i) {
    c.candidates += raster.candidates()[i] != PrimaryRaster::kNone;
    if (!traced.hit(i)) continue;
    ++c.hits;
    if (rastered.primitive[i] != traced.primitive[i] || rastered.mesh[i] != traced.mesh[i])
      continue;
    ++c.same;
    const double d = glm::length(traced.position[i] - camera.origin);
    c.worst_position = std::max(c.worst_position,
                                double(glm::length(rastered.position[i] - traced.position[i])) / d);
  }
  return c;
}

void expect_same_surfaces(const Compared& c, double share = 0.999) {
  ASSERT_GT(c.hits, 0u);
  EXPECT_GE(double(c.same), share * double(c.hits)) << c.same << " of " << c.hits;
  EXPECT_LT(c.worst_position, 1e-4);
  // The raster proposes the surfaces: a candidate at (nearly) every pixel with a hit.
  EXPECT_GE(double(c.candidates), share * double(c.hits));
}

TEST(PrimaryRaster, PaysOnlyWithEnoughPixelsPerTriangle) {
  EXPECT_TRUE(raster_pays(32, 512, 512));     // the Cornell box
  EXPECT_TRUE(raster_pays(4089, 640, 360));   // oa_dm4, 56 pixels a triangle
  EXPECT_TRUE(raster_pays(16384, 512, 512));  // 16 pixels a triangle: the line
  EXPECT_FALSE(raster_pays(16385, 512, 512));
  EXPECT_FALSE(raster_pays(60014, 512, 512));  // cubes:5000, slower rasterised
  EXPECT_FALSE(raster_pays(1000010, 512, 512));
  EXPECT_FALSE(raster_pays(1, 0, 0));
}

TEST(PrimaryRaster, CornellBoxSurfacesAreTheTracedOnes) {
  expect_same_surfaces(compare_with_rays(make_cornell(), 97, 61));
}

TEST(PrimaryRaster, ManySmallTrianglesAndSlivers) {
  // Cubes seen from outside: many small triangles, edges everywhere, triangles edge-on.
  expect_same_surfaces(compare_with_rays(make_cubes(300, 7), 160, 120));
}

TEST(PrimaryRaster, SphereLightsAreSeen) {
  Scene s = make_cornell();
  s.lights.clear();
  s.lights.push_back(Light::sphere(vec3(0.0f, 0.3f, 0.0f), 0.2f, vec3(5.0f)));
  s.finalize();
  // (compare_with_rays counts triangle hits: the sphere's pixels must have none, as traced.)
  expect_same_surfaces(compare_with_rays(s, 80, 80));
}

TEST(PrimaryRaster, CutOutsAreTraced) {
  // A quad whose right half is cut out (alpha texels 1, 1, 0, 0) over the Cornell box's floor:
  // through its hole the traced rays see the floor, and so must the raster's G-buffer.
  Scene s = make_cornell();
  const uint32_t leaf = scene_test::add_half_cut_out_material(s);
  Mesh quad = scene_test::quad_mesh("leaf", vec3(-0.4f, 0.1f, -0.4f), vec3(0.8f, 0.0f, 0.0f),
                                    vec3(0.0f, 0.0f, 0.8f), leaf);
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.meshes.push_back(quad);
  s.finalize();
  expect_same_surfaces(compare_with_rays(s, 90, 90));
}

TEST(PrimaryRaster, GeometryAtTheEyeIsLeftToTheRays) {
  // A triangle across the view a hair in front of the eye: nearer than any near plane a raster
  // could use, so build refuses and the G-buffer traces every ray.
  Scene s = make_cornell();
  const vec3 eye = s.camera.position;
  const vec3 ahead = glm::normalize(s.camera.look_at - eye);
  const vec3 side = glm::normalize(glm::cross(ahead, vec3(0, 1, 0)));
  const vec3 c = eye + ahead * 1e-7f;
  Mesh veil;
  veil.name = "veil";
  veil.positions = {c - side - vec3(0, 1, 0), c + side - vec3(0, 1, 0), c + vec3(0, 1, 0)};
  veil.triangles = {{0, 1, 2}};
  veil.materials = {0};
  s.meshes.push_back(veil);
  s.finalize();
  const SceneData data = SceneData::from(s);
  const CameraRays camera = CameraRays::from(s.camera, 32, 32);
  PrimaryRaster raster;
  EXPECT_FALSE(raster.build(data.view(), camera, vec2(0.5f), 32, 32));
}

TEST(PrimaryRaster, InsideAnOpenArenaLevel) {
  const std::string maps = "/usr/share/games/openarena/baseoa/pak1-maps.pk3";
  if (!std::filesystem::exists(maps))
    GTEST_SKIP() << maps << " is missing: install openarena-081-maps (scripts/setup.sh)";
  // The spawn point's view: walls, floors and stairs around the camera, some behind it.
  const Scene s = load_scene(maps + ":maps/oa_dm4.bsp");
  expect_same_surfaces(compare_with_rays(s, 200, 112));
}

}  // namespace
}  // namespace bounce
