// Primary visibility by rasterisation (primary_raster.h): the triangle test on its own, and the
// G-buffer it gives against the one a traced ray per pixel gives, on scenes that try its edges:
// slivers and many small triangles, sphere lights, cut-outs, a camera inside a real level, and
// geometry closer to the eye than the raster's near plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "bounce/render/gbuffer.h"
#include "bounce/render/gbuffer_kernel.h"
#include "bounce/render/primary_raster.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"
#include "scene/checker_texture.h"
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

// Every field of the raster's G-buffer, at every pixel whose camera ray meets its candidate,
// against the per-pixel kernel (gbuffer_triangle_pixel, reading the triangle's form) on that
// candidate: the runs of pixels that share a candidate are evaluated as vector code, eight
// lanes at a time, whose arithmetic may round differently (fused multiply-adds), never more. (A
// weight may move by 1e-5 on a far triangle, where the edge test subtracts nearly equal terms;
// the position it gives stays within 2e-5 of the distance.)
// Returns the pixels compared.
size_t expect_runs_equal_the_kernel(const Scene& scene, int w, int h) {
  const SceneData data = SceneData::from(scene);
  const SceneView view = data.view();
  const std::unique_ptr<Tracer> tracer = make_embree_tracer(scene);
  const CameraRays camera = CameraRays::from(scene.camera, w, h);
  const vec2 subpixel(0.3f, 0.7f);
  PrimaryRaster raster;
  EXPECT_TRUE(raster.build(view, camera, subpixel, w, h));
  GBuffer rastered, kernel;
  rastered.resize(w, h);
  kernel.resize(w, h);
  build_gbuffer(view, *tracer, camera, subpixel, rastered, &raster);
  const GBufferView k = kernel.view();
  size_t compared = 0, mismatched = 0;
  const auto close = [](vec3 a, vec3 b, float scale) {
    return glm::length(a - b) <= 2e-5f * std::max(scale, 1.0f);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = k.index(x, y);
      const uint32_t c = raster.candidates()[i];
      if (c == PrimaryRaster::kNone) continue;
      const RasterTriangle& r = raster.triangles()[c];
      const SurfaceTriangle t = surface_triangle(view, r.mesh, r.triangle);
      if (t.material->has_cutouts()) continue;  // traced
      Ray ray;
      ray.origin = camera.origin;
      ray.direction = camera.direction(float(x) + subpixel.x, float(y) + subpixel.y);
      ray.tmin = 0.0f;
      Hit hit;
      hit.mesh = r.mesh;
      hit.triangle = r.triangle;
      if (!TriangleFromOrigin::make(t.p0, t.p1, t.p2, camera.origin)
               .intersect(ray.direction, ray.tmin, ray.tmax, hit.t, hit.barycentric))
        continue;  // traced
      gbuffer_triangle_pixel(view, camera.forward, camera.pixel_spread(), ray, hit, t,
                             view.triangle_id(r.mesh, r.triangle), i, k);
      ++compared;
      const float d = kernel.depth[i];
      const bool same =
          rastered.primitive[i] == kernel.primitive[i] && rastered.mesh[i] == kernel.mesh[i] &&
          close(rastered.position[i], kernel.position[i], d) &&
          std::abs(rastered.depth[i] - d) <= 2e-5f * std::max(d, 1.0f) &&
          glm::length(rastered.barycentric[i] - kernel.barycentric[i]) <= 1e-4f &&
          close(rastered.normal[i], kernel.normal[i], 1.0f) &&
          close(rastered.geometric_normal[i], kernel.geometric_normal[i], 1.0f) &&
          close(rastered.albedo[i], kernel.albedo[i], 1.0f) &&
          close(rastered.f0[i], kernel.f0[i], 1.0f) &&
          close(rastered.emission[i], kernel.emission[i], max_component(kernel.emission[i])) &&
          std::abs(rastered.roughness[i] - kernel.roughness[i]) <= 1e-5f;
      if (!same && ++mismatched <= 3)
        ADD_FAILURE() << "pixel (" << x << ", " << y << "): triangle " << rastered.primitive[i]
                      << " against " << kernel.primitive[i] << ", depth " << rastered.depth[i]
                      << " against " << d << ", barycentric " << rastered.barycentric[i].x << " "
                      << rastered.barycentric[i].y << " against " << kernel.barycentric[i].x << " "
                      << kernel.barycentric[i].y << ", albedo " << rastered.albedo[i].x
                      << " against " << kernel.albedo[i].x << ", emission "
                      << rastered.emission[i].x << " against " << kernel.emission[i].x;
    }
  EXPECT_EQ(mismatched, 0u) << "of " << compared;
  return compared;
}

TEST(PrimaryRaster, RunsOfACandidateEqualThePerPixelKernel) {
  // The Cornell box: flat, untextured surfaces (a form of their own), most pixels in long runs.
  EXPECT_GT(expect_runs_equal_the_kernel(make_cornell(), 101, 67), 3500u);
  // Textured quads over the box: one with normals (a level's form), one without and glowing
  // through an emission texture (a form without a loop of its own, read from the triangle).
  Scene s = make_cornell();
  s.textures.push_back(checker_texture());
  Material painted;
  painted.albedo = vec3(0.8f);
  painted.albedo_texture = int(s.textures.size() - 1);
  s.materials.push_back(painted);
  painted.emission = vec3(2.0f);
  painted.emission_texture = painted.albedo_texture;
  s.materials.push_back(painted);
  Mesh smooth = scene_test::quad_mesh("smooth", vec3(-0.45f, 0.05f, -0.45f), vec3(0.5f, 0, 0),
                                      vec3(0, 0.1f, 0.5f), uint32_t(s.materials.size() - 2));
  smooth.uvs = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  smooth.normals.assign(4, glm::normalize(vec3(0.0f, 0.5f, -0.1f)));
  Mesh glowing = scene_test::quad_mesh("glowing", vec3(0.05f, 0.02f, -0.3f), vec3(0, 0, 0.6f),
                                       vec3(0.4f, 0, 0), uint32_t(s.materials.size() - 1));
  glowing.uvs = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  s.meshes.push_back(smooth);
  s.meshes.push_back(glowing);
  s.finalize();
  EXPECT_GT(expect_runs_equal_the_kernel(s, 90, 90), 4000u);
  // Many small triangles: short runs, most of them shorter than a block of eight.
  EXPECT_GT(expect_runs_equal_the_kernel(make_cubes(300, 7), 160, 120), 3000u);
  // A level's textured surfaces, normals interpolated, some glowing.
  const std::string maps = "/usr/share/games/openarena/baseoa/pak1-maps.pk3";
  if (!std::filesystem::exists(maps))
    GTEST_SKIP() << maps << " is missing: install openarena-081-maps (scripts/setup.sh)";
  EXPECT_GT(expect_runs_equal_the_kernel(load_scene(maps + ":maps/oa_dm4.bsp"), 200, 112), 15000u);
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
