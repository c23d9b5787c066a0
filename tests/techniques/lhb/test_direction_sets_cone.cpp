// The cone approximation (seed 001 section 5.5): with 320 icosahedron directions, cones of
// 12.6 degrees around them overlap and cones of 16.3 degrees cover every direction (the seed's
// Fig. 5.5), while the bare directions (delta functions) cover almost nothing; and the disc
// jitter of the projected origin realises a cone: radius r texels at distance D reaches
// atan(r * texel / D).
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/core/qmc.h"
#include "bounce/core/sampling.h"
#include "bounce/techniques/lhb/direction_sets.h"
#include "bounce/techniques/lhb/layered_hit_buffers.h"
#include "bounce/techniques/lhb/lhb_query.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

constexpr float kDegree = 0.017453292519943295f;

// The share of evenly spread directions within half_angle of some direction of the set, and
// the mean number of cones over a direction.
struct Coverage {
  double covered = 0.0, mean_overlap = 0.0;
};
Coverage cone_coverage(const DirectionSet& set, float half_angle) {
  const int n = 20000;
  const float cos_a = std::cos(half_angle);
  int covered = 0;
  long overlap = 0;
  for (int k = 0; k < n; ++k) {
    const vec3 q = sample_uniform_sphere(hammersley(uint32_t(k), uint32_t(n)));
    int cones = 0;
    for (const vec3& d : set.directions()) cones += glm::dot(q, d) >= cos_a ? 1 : 0;
    covered += cones > 0 ? 1 : 0;
    overlap += cones;
  }
  return {double(covered) / n, double(overlap) / n};
}

TEST(DirectionSetsCone, IcosahedronConesCoverTheSphereAsInTheSeed) {
  const DirectionSet set = DirectionSet::icosahedron(2);
  const Coverage delta = cone_coverage(set, 0.5f * kDegree);
  const Coverage small = cone_coverage(set, 12.6f * kDegree);
  const Coverage full = cone_coverage(set, 16.3f * kDegree);
  RecordProperty("cover_radius_deg",
                 std::to_string(evaluate_direction_set(set, 1 << 16).worst_error_deg));
  EXPECT_LT(delta.covered, 0.03);      // delta functions: banding
  EXPECT_GT(small.mean_overlap, 2.0);  // 12.6 degrees: cones overlap
  EXPECT_EQ(full.covered, 1.0);        // 16.3 degrees: everything is covered
  // Our measured cover radius (9.9 degrees) lies below both of the seed's angles.
  EXPECT_LT(evaluate_direction_set(set, 1 << 16).worst_error_deg, 12.6);
}

TEST(DirectionSetsCone, DiscJitterRealisesTheConeAngle) {
  // One wall facing the buffer's direction (-z), a distance D in front of the origin.
  Scene scene;
  scene.source = "wall";
  scene.materials.push_back(Material{});
  scene.meshes.push_back(
      scene_test::quad_mesh("wall", vec3(-2.0f, -2.0f, 1.0f), vec3(0, 4, 0), vec3(4, 0, 0), 0));
  scene.finalize();
  const vec3 d(0.0f, 0.0f, 1.0f);
  LayeredHitBuffers buffers;
  LhbSettings settings;
  settings.size = 256;
  buffers.build(scene, std::span<const vec3>(&d, 1), settings);
  const LhbView view = buffers.view();
  const vec3 origin(0.0f, 0.0f, 0.0f);
  const float distance = 1.0f;
  for (float degrees : {4.0f, 12.6f, 16.3f}) {
    const float radius = distance * std::tan(degrees * kDegree) / buffers.texel_size(0);
    float widest = 0.0f;
    for (int k = 0; k < 512; ++k) {
      const vec2 jitter = radius * sample_concentric_disk(hammersley(uint32_t(k), 512));
      const LhbHit hit = lhb_closest(view, 0, origin, 0.0f, jitter);
      ASSERT_TRUE(hit.valid());
      const vec3 p = hit.point;
      EXPECT_NEAR(p.z, 1.0f, 1e-4f);
      widest = std::max(widest, std::acos(glm::dot(glm::normalize(p - origin), d)));
    }
    EXPECT_NEAR(widest / kDegree, degrees, 0.3f) << "radius " << radius << " texels";
  }
}

}  // namespace
}  // namespace bounce
