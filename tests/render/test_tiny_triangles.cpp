// Triangles a few float steps wide (a fuzzed Quake map held one 5.7e-38 m across): their cross
// product underflows, so a plain normalize gave a NaN normal, NaN photon directions, and Embree's
// ray-validity assertion aborted the process. The unit normal is computed from scaled edges.
#include <cmath>

#include <gtest/gtest.h>

#include "bounce/eval/render_image.h"
#include "bounce/scene/mesh.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

TEST(TinyTriangles, UnitNormalSurvivesUnderflowAndDegeneracy) {
  const float tiny = 5.7e-38f;
  const vec3 n = triangle_unit_normal(vec3(0.0f), vec3(tiny, 0.0f, 0.0f), vec3(0.0f, tiny, 0.0f));
  EXPECT_FLOAT_EQ(n.z, 1.0f);
  EXPECT_FLOAT_EQ(n.x, 0.0f);
  // Its plain cross product is 0 in float: the case the scaled edges exist for.
  const vec3 plain = triangle_normal_area2(vec3(0.0f), vec3(tiny, 0.0f, 0.0f), vec3(0, tiny, 0));
  EXPECT_EQ(glm::length(plain), 0.0f);
  // A thin sliver keeps its orientation; an ordinary triangle gets the ordinary normal.
  const vec3 thin = triangle_unit_normal(vec3(0.0f), vec3(0.0f, 0.0f, 2.0f), vec3(0, tiny, 1));
  EXPECT_NEAR(thin.x, -1.0f, 1e-6f);
  const vec3 usual = triangle_unit_normal(vec3(0.0f), vec3(0, 0, 1), vec3(1, 0, 0));
  EXPECT_NEAR(usual.y, 1.0f, 1e-6f);
  // Degenerate (collinear or a point): a finite fallback, never NaN.
  const vec3 line = triangle_unit_normal(vec3(0.0f), vec3(1.0f), vec3(2.0f));
  EXPECT_TRUE(std::isfinite(line.x) && std::isfinite(line.y) && std::isfinite(line.z));
}

// The fuzzed map's shape: one wall a few float steps thick, lit only by the default sky, renders
// with every photon technique instead of aborting.
TEST(TinyTriangles, ASceneOfUnderflowingTrianglesRenders) {
  Scene s;
  s.source = "tiny triangles";
  s.materials.push_back(Material{});
  const float tiny = 5.7e-38f;
  Mesh wall;
  wall.name = "wall";
  wall.positions = {vec3(0, 0, 0), vec3(tiny, 0, 0), vec3(0, 2.4f, -1.6f), vec3(tiny, 2.4f, 0)};
  wall.triangles = {uvec3(0, 1, 2), uvec3(1, 3, 2)};
  wall.materials = {0, 0};
  s.meshes.push_back(wall);
  s.lights.push_back(Light::environment(vec3(1.0f)));
  s.finalize();
  for (const char* technique : {"tiled", "vertex", "direct"}) {
    const Image image = render_image(s, technique, FrameSettings{8, 8, 1}, 1);
    for (const vec3& p : image.pixels())
      EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << technique;
  }
}

}  // namespace
}  // namespace bounce
