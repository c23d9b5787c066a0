// The photon map's irradiance on a plane lit by a point light matches the analytic
// E = I h / (h^2 + r^2)^(3/2); with the sphere slice, the leak scene's wall keeps light on its
// lit side.
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/scene/load.h"
#include "tests/techniques/vertex/vertex_test_util.h"

namespace bounce {
namespace {

using vertex_test::VertexRun;

Scene lit_plane(float height, float intensity) {
  Scene scene;
  Material white;
  white.name = "white";
  white.albedo = vec3(0.5f);
  scene.materials = {white};
  Mesh plane;
  plane.name = "plane";
  plane.positions = {vec3(-20, 0, -20), vec3(20, 0, -20), vec3(20, 0, 20), vec3(-20, 0, 20)};
  plane.triangles = {uvec3(0, 2, 1), uvec3(0, 3, 2)};  // facing +y
  plane.materials = {0, 0};
  scene.meshes.push_back(plane);
  scene.lights.push_back(Light::point(vec3(0, height, 0), vec3(intensity)));
  scene.finalize();
  return scene;
}

TEST(VertexIrradiance, UniformlyLitPlaneMatchesTheAnalyticValue) {
  const float h = 1.0f, intensity = 10.0f;
  const Scene scene = lit_plane(h, intensity);
  // First hits only, one frame of many photons, k large: the estimate's noise is ~1/sqrt(k).
  VertexRun run(scene, {{"store_direct_light", "true"},
                        {"recursion_depth", "0"},
                        {"roulette", "false"},
                        {"photons_from_light", "400000"},
                        {"accumulation_frames", "1"},
                        {"max_search_count", "400"},
                        {"mesh_refinement", "0"}});
  run.frame(scene);
  ASSERT_GT(run.technique->photon_count(), 150000u);  // half the photons go down
  double sum_ratio = 0.0;
  int n = 0;
  for (const float r : {0.0f, 0.1f, 0.2f, 0.3f, 0.5f}) {
    for (const float phi : {0.0f, 1.3f, 2.9f, 4.4f}) {
      const vec3 x(r * std::cos(phi), 0.0f, r * std::sin(phi));
      const float expected = intensity * h / std::pow(h * h + r * r, 1.5f);
      const vec3 e = run.irradiance(x, vec3(0, 1, 0));
      EXPECT_NEAR(e.x, expected, 0.12f * expected) << "r " << r;
      sum_ratio += e.x / expected;
      ++n;
    }
  }
  // On average over the points: the estimator is normalised (within its curvature bias).
  EXPECT_NEAR(sum_ratio / n, 1.0, 0.03);
  // The other side of the plane has no light (the side test).
  EXPECT_EQ(run.irradiance(vec3(0.0f), vec3(0, -1, 0)).x, 0.0f);
}

// The ring's flux scale: a map of F frames gives the same irradiance as one frame.
TEST(VertexIrradiance, AccumulationFramesDoNotChangeTheBrightness) {
  const Scene scene = lit_plane(1.0f, 10.0f);
  const auto mean_irradiance = [&](const char* frames, int rendered) {
    VertexRun run(scene, {{"store_direct_light", "true"},
                          {"recursion_depth", "0"},
                          {"roulette", "false"},
                          {"photons_from_light", "50000"},
                          {"accumulation_frames", frames},
                          {"max_search_count", "200"},
                          {"mesh_refinement", "0"}});
    for (int k = 0; k < rendered; ++k) run.frame(scene);
    double sum = 0.0;
    for (int i = 0; i < 16; ++i)
      sum += run.irradiance(vec3(0.02f * i - 0.16f, 0, 0.01f * i), vec3(0, 1, 0)).x;
    return sum / 16.0;
  };
  const double one = mean_irradiance("1", 1);
  const double four_partly = mean_irradiance("4", 2);  // two of four slots filled
  const double four = mean_irradiance("4", 6);
  EXPECT_NEAR(one, 10.0, 0.6);
  EXPECT_NEAR(four_partly, one, 0.05 * one);
  EXPECT_NEAR(four, one, 0.05 * one);
}

// The leak scene: a 2 cm wall between a lit and a dark half. Points on the wall's dark face
// (x = 2.01, facing +x) gather photons from its lit face 2 cm away unless the sphere slice (or
// the side test, off here) turns them away.
TEST(VertexIrradiance, SphereSliceStopsTheLeakThroughTheWall) {
  const Scene scene = make_leak();
  const auto dark_face = [&](bool slice) {
    VertexRun run(scene, {{"use_sphere_slice", slice ? "true" : "false"},
                          {"direction_test", "false"},
                          {"photons_from_light", "2000"},
                          {"accumulation_frames", "1"},
                          {"mesh_refinement", "0"}});
    run.frame(scene);
    double dark = 0.0, lit = 0.0;
    for (float y = 0.9f; y < 1.7f; y += 0.2f)
      for (float z = 1.0f; z < 3.01f; z += 0.5f) {
        dark += run.irradiance(vec3(2.01f, y, z), vec3(1, 0, 0)).x;
        lit += run.irradiance(vec3(1.99f, y, z), vec3(-1, 0, 0)).x;
      }
    return std::pair(dark, lit);
  };
  const auto [dark_without, lit_without] = dark_face(false);
  const auto [dark_with, lit_with] = dark_face(true);
  RecordProperty("dark_without_slice", std::to_string(dark_without));
  RecordProperty("dark_with_slice", std::to_string(dark_with));
  EXPECT_GT(lit_with, 0.0);
  EXPECT_GT(dark_without, 0.3 * lit_without);  // without: the dark face shows the lit one's light
  EXPECT_EQ(dark_with, 0.0);                   // with: none
  EXPECT_NEAR(lit_with, lit_without, 0.5 * lit_without);
}

}  // namespace
}  // namespace bounce
