// Longest-edge refinement: it reaches the target count, stays conforming (no vertex of the
// refined mesh lies inside another triangle's edge), covers each coarse triangle exactly, and a
// G-buffer hit (coarse triangle, barycentrics) finds the refined triangle that holds it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "bounce/core/rng.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/vertex/refined_mesh.h"

namespace bounce {
namespace {

// Whether p lies strictly inside segment a-b.
bool inside_segment(vec3 p, vec3 a, vec3 b) {
  const vec3 ab = b - a, ap = p - a;
  const float len2 = glm::dot(ab, ab);
  const float t = glm::dot(ap, ab) / len2;
  if (t <= 1e-5f || t >= 1.0f - 1e-5f) return false;
  return glm::length(ap - t * ab) < 1e-6f * std::sqrt(len2);
}

TEST(RefinedMesh, ReachesTheTargetAndStaysConforming) {
  const Scene scene = make_cornell();
  for (const uint32_t added : {0u, 1u, 300u, 2000u}) {
    RefinedMesh r;
    r.build(scene, added);
    const uint32_t coarse = r.coarse_triangles();
    EXPECT_EQ(coarse, scene.triangle_offsets.back() + scene.meshes.back().triangle_count());
    // A conforming split adds one triangle per triangle on the edge (two inside a mesh).
    EXPECT_GE(r.triangles(), coarse + added);
    EXPECT_LE(r.triangles(), coarse + added + 8);
    // No T-junctions: no refined point lies inside a refined edge.
    const auto& pts = r.point_positions();
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const uvec3& t : r.leaf_points())
      for (int e = 0; e < 3; ++e) edges.insert(std::minmax(t[e], t[(e + 1) % 3]));
    size_t junctions = 0;
    for (const auto& [a, b] : edges)
      for (size_t p = 0; p < pts.size(); ++p)
        if (p != a && p != b && inside_segment(pts[p], pts[a], pts[b])) ++junctions;
    EXPECT_EQ(junctions, 0u) << "added " << added;
  }
}

TEST(RefinedMesh, SplitsTheLongestEdgesFirst) {
  const Scene scene = make_cornell();
  RefinedMesh r;
  r.build(scene, 3000);
  // After refinement no edge is much longer than the shortest longest-edge split last: every
  // refined triangle's longest edge is within a factor 2 of the others' (plus the coarse short
  // ones, which were never split).
  float longest = 0.0f;
  const auto& pts = r.point_positions();
  for (const uvec3& t : r.leaf_points())
    for (int e = 0; e < 3; ++e)
      longest = std::max(longest, glm::length(pts[t[e]] - pts[t[(e + 1) % 3]]));
  EXPECT_LT(longest, 0.1f);  // the 0.55 m walls (0.78 m diagonals), split to a few cm
}

TEST(RefinedMesh, LocatesEveryHitAndCoversTheCoarseTriangles) {
  const Scene scene = make_cornell();
  RefinedMesh r;
  r.build(scene, 2000);
  const RefinedMeshView v = r.view();
  // Area: the refined triangles of each coarse triangle sum to its area.
  std::vector<double> area(r.coarse_triangles(), 0.0);
  const auto& pts = r.point_positions();
  for (uint32_t t = 0; t < v.leaf_count; ++t) {
    const uvec3 p = r.leaf_points()[t];
    area[v.leaf_coarse[t]] +=
        0.5 * glm::length(glm::cross(pts[p.y] - pts[p.x], pts[p.z] - pts[p.x]));
  }
  for (uint32_t m = 0; m < scene.meshes.size(); ++m)
    for (uint32_t t = 0; t < scene.meshes[m].triangle_count(); ++t) {
      const double coarse_area = 0.5 * glm::length(scene.meshes[m].face_normal_area2(t));
      EXPECT_NEAR(area[scene.triangle_offsets[m] + t], coarse_area, 1e-5 + 1e-4 * coarse_area);
    }
  // Random hits: the located triangle's corners, weighted, give back the hit's position.
  Pcg32 rng(3);
  for (int k = 0; k < 5000; ++k) {
    const uint32_t m = rng.next_u32() % scene.meshes.size();
    const Mesh& mesh = scene.meshes[m];
    const uint32_t t = rng.next_u32() % mesh.triangle_count();
    vec2 b(rng.next_float(), rng.next_float());
    if (b.x + b.y > 1.0f) b = vec2(1.0f) - b;
    const uvec3 tri = mesh.triangles[t];
    const vec3 hit = (1.0f - b.x - b.y) * mesh.positions[tri.x] + b.x * mesh.positions[tri.y] +
                     b.y * mesh.positions[tri.z];
    const RefinedPoint p = locate_refined(v, scene.triangle_offsets[m] + t, b);
    ASSERT_LT(p.leaf, v.leaf_count);
    EXPECT_EQ(v.leaf_coarse[p.leaf], scene.triangle_offsets[m] + t);
    const uvec3 corners = r.leaf_points()[p.leaf];
    const vec3 back =
        p.weights.x * pts[corners.x] + p.weights.y * pts[corners.y] + p.weights.z * pts[corners.z];
    EXPECT_LT(glm::length(back - hit), 1e-5f);
    EXPECT_GE(std::min({p.weights.x, p.weights.y, p.weights.z}), 0.0f);
  }
}

// A refined triangle's map gives its corners the weights (1, 0, 0), (0, 1, 0), (0, 0, 1) and its
// centroid a third each; a triangle without area has no point on it.
TEST(RefinedMesh, LeafMapsWeighTheCornersAndRefuseDegenerateTriangles) {
  const vec2 c[3] = {{0.25f, 0.125f}, {0.75f, 0.1875f}, {0.3125f, 0.625f}};
  LeafMap map = LeafMap::of(c[0], c[1], c[2]);
  RefinedMeshView v;
  v.leaf_map = &map;
  vec3 w;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(weights_on_leaf(v, 0, c[k], w));
    EXPECT_NEAR(w[k], 1.0f, 1e-6f);
    EXPECT_NEAR(w[(k + 1) % 3], 0.0f, 1e-6f);
  }
  EXPECT_TRUE(weights_on_leaf(v, 0, (c[0] + c[1] + c[2]) / 3.0f, w));
  EXPECT_NEAR(glm::length(w - vec3(1.0f / 3.0f)), 0.0f, 1e-6f);
  EXPECT_FALSE(weights_on_leaf(v, 0, c[1] + (c[1] - c[0]), w));  // beyond a corner
  map = LeafMap::of(c[0], c[1], 2.0f * c[1] - c[0]);             // collinear corners
  EXPECT_FALSE(weights_on_leaf(v, 0, c[1], w));
  EXPECT_EQ(w, vec3(1.0f, 0.0f, 0.0f));
}

// A hint (a neighbouring pixel's refined triangle) changes nothing: where the point lies on the
// hinted triangle it is taken, with the weights the descent finds; a hint on another triangle,
// or on another coarse triangle, falls back to the descent.
TEST(RefinedMesh, LocatingWithAHintFindsWhatTheDescentFinds) {
  const Scene scene = make_cornell();
  RefinedMesh r;
  r.build(scene, 2000);
  const RefinedMeshView v = r.view();
  Pcg32 rng(5);
  int taken = 0;
  for (int k = 0; k < 5000; ++k) {
    const uint32_t coarse = rng.next_u32() % r.coarse_triangles();
    vec2 b(rng.next_float(), rng.next_float());
    if (b.x + b.y > 1.0f) b = vec2(1.0f) - b;
    const RefinedPoint plain = locate_refined(v, coarse, b);
    // Its own triangle, a triangle elsewhere, and the triangle of a point nearby.
    vec2 near = b + vec2(rng.next_float() - 0.5f, rng.next_float() - 0.5f) * 0.02f;
    near = glm::clamp(near, 0.0f, 1.0f);
    if (near.x + near.y > 1.0f) near /= near.x + near.y;
    for (const uint32_t hint :
         {plain.leaf, rng.next_u32() % v.leaf_count, locate_refined(v, coarse, near).leaf}) {
      const RefinedPoint hinted = locate_refined(v, coarse, b, hint);
      // Off the split lines (every weight above rounding) the triangle is the descent's.
      if (std::min({plain.weights.x, plain.weights.y, plain.weights.z}) > 1e-4f) {
        EXPECT_EQ(hinted.leaf, plain.leaf) << k;
        EXPECT_EQ(hinted.weights, plain.weights) << k;
      }
      EXPECT_EQ(v.leaf_coarse[hinted.leaf], coarse);
      taken += hinted.leaf == hint;
    }
  }
  EXPECT_GT(taken, 5000);  // the own triangle always, the nearby one often
}

// Keys are shared: a refined vertex inside a flat wall is one estimate for all its triangles.
TEST(RefinedMesh, EstimatePointsAreSharedBetweenTriangles) {
  const Scene scene = make_cornell();
  RefinedMesh r;
  r.build(scene, 2000);
  EXPECT_LT(double(r.keys()), 0.8 * r.triangles());
}

}  // namespace
}  // namespace bounce
