#include <cmath>

#include <gtest/gtest.h>

#include "bounce/core/rng.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/surface.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "checker_texture.h"

namespace bounce {
namespace {

// A textured quad with per-vertex normals and uvs, a flat emissive triangle (an area light) in a
// second mesh, and the Cornell box around them: every kind of array a SceneView points to.
Scene textured_scene() {
  Scene s = make_cornell();
  s.textures.push_back(checker_texture());
  Material textured;
  textured.name = "textured";
  textured.albedo = vec3(0.5f);
  textured.albedo_texture = 0;
  textured.f0 = vec3(0.04f);
  textured.roughness = 0.3f;
  s.materials.push_back(textured);
  Material glow;
  glow.name = "glow";
  glow.emission = vec3(3.0f, 2.0f, 1.0f);
  s.materials.push_back(glow);
  Mesh quad;
  quad.name = "quad";
  quad.positions = {vec3(0.1f, 0.1f, 0.2f), vec3(0.4f, 0.1f, 0.25f), vec3(0.4f, 0.4f, 0.2f),
                    vec3(0.1f, 0.4f, 0.25f)};
  quad.normals = {glm::normalize(vec3(0.1f, 0.0f, -1.0f)), vec3(0.0f, 0.0f, -1.0f),
                  glm::normalize(vec3(0.0f, 0.2f, -1.0f)), vec3(0.0f, 0.0f, -1.0f)};
  quad.uvs = {vec2(0.0f), vec2(1.5f, 0.0f), vec2(1.5f, 1.5f), vec2(0.0f, 1.5f)};
  quad.triangles = {uvec3(0, 1, 2), uvec3(0, 2, 3)};
  quad.materials = {uint32_t(s.materials.size() - 2), uint32_t(s.materials.size() - 2)};
  s.meshes.push_back(quad);
  Mesh lamp;
  lamp.name = "lamp";
  lamp.positions = {vec3(0.3f, 0.5f, 0.3f), vec3(0.35f, 0.5f, 0.3f), vec3(0.3f, 0.5f, 0.4f)};
  lamp.triangles = {uvec3(0, 1, 2)};
  lamp.materials = {uint32_t(s.materials.size() - 1)};
  s.meshes.push_back(lamp);
  s.lights.push_back(Light::sphere(vec3(0.2f, 0.3f, 0.3f), 0.05f, vec3(4.0f)));
  s.lights.push_back(Light::spot(vec3(0.3f, 0.5f, 0.2f), vec3(0, -1, 0), vec3(2.0f), 20, 30));
  s.finalize();
  return s;
}

// Equal up to rounding: the host's surface_at and the view's are the same code compiled in two
// places, and the compiler may contract a multiply and an add into one in either (a normal's
// 1e-9 component once came out with the other sign). A view reading the wrong vertex, material or
// texel is off by far more.
void expect_same_vec(vec3 a, vec3 b, const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], 1e-6f + 4e-7f * std::fabs(b[c])) << what << " component " << c;
}

void expect_same_surface(const SurfaceHit& a, const SurfaceHit& b) {
  expect_same_vec(a.position, b.position, "position");
  expect_same_vec(a.normal, b.normal, "normal");
  expect_same_vec(a.geometric_normal, b.geometric_normal, "geometric normal");
  expect_same_vec(a.albedo, b.albedo, "albedo");
  expect_same_vec(a.f0, b.f0, "f0");
  expect_same_vec(a.emission, b.emission, "emission");
  EXPECT_NEAR(a.roughness, b.roughness, 1e-6f);
}

// Every triangle at random barycentrics, from both sides: the view gives the scene's surfaces.
void expect_view_matches_scene(const Scene& scene, const SceneView& view) {
  ASSERT_EQ(view.mesh_count, scene.meshes.size());
  Pcg32 rng(2);
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    ASSERT_EQ(view.meshes[m].triangle_count, scene.meshes[m].triangle_count());
    // SceneData makes each triangle's unit normal once; the scene's surface_at computes it.
    ASSERT_NE(view.meshes[m].face_normals, nullptr);
    for (uint32_t t = 0; t < scene.meshes[m].triangle_count(); ++t) {
      EXPECT_EQ(view.triangle_id(m, t), scene.triangle_offsets[m] + t);
      for (const vec3 direction : {vec3(0.3f, -0.2f, 1.0f), vec3(-0.1f, 0.4f, -1.0f)}) {
        Hit hit;
        hit.t = 1.0f;
        hit.mesh = m;
        hit.triangle = t;
        const float u = rng.next_float();
        hit.barycentric = vec2(u, (1.0f - u) * rng.next_float());
        expect_same_surface(surface_at(view, hit, direction), surface_at(scene, hit, direction));
      }
    }
  }
}

TEST(SceneData, ViewReadsAsTheSceneDoes) {
  const Scene scene = textured_scene();
  const SceneData data = SceneData::from(scene);
  const SceneView view = data.view();
  expect_view_matches_scene(scene, view);

  // The texture really is sampled (not just the material's albedo) and agrees with Texture.
  ASSERT_EQ(view.texture_count, 1u);
  for (const vec2 uv : {vec2(0.1f, 0.2f), vec2(0.75f, 0.3f), vec2(-1.3f, 2.6f)})
    EXPECT_EQ(view.textures[0].sample(uv), scene.textures[0].sample(uv));
  EXPECT_NE(view.textures[0].sample(vec2(0.25f)), view.textures[0].sample(vec2(0.75f)));

  ASSERT_EQ(view.light_count, scene.lights.size());
  for (uint32_t i = 0; i < view.light_count; ++i) {
    EXPECT_TRUE(view.lights[i] == static_cast<const LightRecord&>(scene.lights[i]));
    EXPECT_EQ(view.lights[i].power(1.0f), scene.lights[i].power(1.0f));
  }
  ASSERT_EQ(view.area_light_count, scene.area_lights.size());
  ASSERT_GE(view.area_light_count, 2u);  // the Cornell ceiling light and the lamp
  Pcg32 rng(4);
  for (uint32_t a = 0; a < view.area_light_count; ++a) {
    EXPECT_EQ(view.area_lights[a].power(), scene.area_lights[a].power());
    for (int k = 0; k < 20; ++k) {
      const vec2 u = rng.next2();
      const AreaLightPoint p = sample_area_light_point(view, view.area_lights[a], u);
      const AreaLightPoint q = sample_area_light_point(scene, scene.area_lights[a], u);
      EXPECT_EQ(p.position, q.position);
      EXPECT_EQ(p.normal, q.normal);
    }
  }
  EXPECT_EQ(view.bounds.lo, scene.bounds.lo);
  EXPECT_EQ(view.bounds.hi, scene.bounds.hi);
}

TEST(SceneData, ViewIsPlainDataThatSurvivesAMove) {
  const Scene scene = textured_scene();
  SceneData data = SceneData::from(scene);
  const SceneView before = data.view();
  SceneData moved = std::move(data);
  const SceneView after = moved.view();
  // The arrays are the same memory: moving the owner copies no data and dangles no pointer.
  EXPECT_EQ(before.meshes, after.meshes);
  EXPECT_EQ(before.meshes[0].positions, after.meshes[0].positions);
  EXPECT_EQ(before.materials, after.materials);
  EXPECT_EQ(before.textures, after.textures);
  EXPECT_EQ(before.textures[0].texels, after.textures[0].texels);
  EXPECT_EQ(before.lights, after.lights);
  EXPECT_EQ(before.area_lights, after.area_lights);
  EXPECT_EQ(before.area_lights[0].cdf, after.area_lights[0].cdf);
  expect_view_matches_scene(scene, after);
}

TEST(SceneData, RefreshFollowsMovedVerticesLightsAndMaterials) {
  Scene scene = textured_scene();
  SceneData data = SceneData::from(scene);
  const uint32_t quad = uint32_t(scene.meshes.size() - 2);
  const vec3* positions_before = data.view().meshes[quad].positions;
  for (vec3& p : scene.meshes[quad].positions) p += vec3(0.01f, 0.02f, 0.0f);
  scene.meshes[quad].positions[2].z += 0.1f;  // tilts both triangles: their normals must follow
  for (vec3& n : scene.meshes[quad].normals) n = glm::normalize(n + vec3(0.1f, 0.0f, 0.0f));
  scene.lights[0].position.x += 0.05f;
  scene.materials[0].albedo = vec3(0.1f, 0.2f, 0.3f);
  scene.derive();
  const uint32_t moved[] = {quad};
  data.refresh(scene, moved);
  // Same layout: refreshed in place, the arrays did not move.
  EXPECT_EQ(data.view().meshes[quad].positions, positions_before);
  expect_view_matches_scene(scene, data.view());
  EXPECT_EQ(data.view().lights[0].position, scene.lights[0].position);
  EXPECT_EQ(data.view().materials[0].albedo, vec3(0.1f, 0.2f, 0.3f));

  // A new mesh changes the layout: refresh rebuilds.
  Mesh extra = scene.meshes[quad];
  extra.name = "extra";
  for (vec3& p : extra.positions) p.z += 0.1f;
  scene.meshes.push_back(extra);
  scene.derive();
  data.refresh(scene, {});
  expect_view_matches_scene(scene, data.view());
}

}  // namespace
}  // namespace bounce
