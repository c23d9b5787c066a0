// Bezier patch tessellation: exact on the control grid's corners and borders, and watertight
// where patches meet, in one face or across two faces walking a border in opposite directions.
#include <map>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "bounce/core/error.h"
#include "bounce/scene/quake/patch.h"

namespace bounce::quake {
namespace {

BspVertex control(float x, float y, float z) {
  BspVertex v;
  v.position = {x, y, z};
  v.normal = {0, 0, 1};
  v.uv = {x / 64.0f, y / 64.0f};
  return v;
}

// A width x height control grid over a bumpy sheet, with irrational-ish coordinates so that
// rounding would show.
std::vector<BspVertex> sheet(int width, int height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> bump(-7.3f, 7.3f);
  std::vector<BspVertex> out;
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) out.push_back(control(c * 16.37f, r * 13.11f, bump(rng)));
  return out;
}

using Key = std::tuple<float, float, float>;
Key key(vec3 p) {
  return {p.x, p.y, p.z};
}

TEST(BspPatch, QuadraticStepIsExactlySymmetric) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1000.0f, 1000.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    for (int level : {1, 2, 3, 4, 7, 8, 16})
      for (int k = 0; k <= level; ++k)
        ASSERT_EQ(bezier_step(a, b, c, k, level), bezier_step(c, b, a, level - k, level));
    EXPECT_EQ(bezier_step(a, b, c, 0, 5), a);
    EXPECT_EQ(bezier_step(a, b, c, 5, 5), c);
  }
}

TEST(BspPatch, CountsCornersAndMidpoint) {
  const std::vector<BspVertex> grid = sheet(5, 3, 1);  // two patches side by side
  PatchMesh mesh;
  tessellate_patch(grid, 5, 3, 4, mesh);
  EXPECT_EQ(mesh.vertices.size(), size_t(2 * 4 + 1) * size_t(4 + 1));
  EXPECT_EQ(mesh.triangles.size(), size_t(2 * 4 * 4 * 2));
  // Corners of the face are its corner control points.
  for (auto [row, col, ctrl] : {std::tuple{0, 0, 0}, {0, 8, 4}, {4, 0, 10}, {4, 8, 14}}) {
    const auto& p = mesh.vertices[size_t(row * 9 + col)].position;
    const auto& q = grid[size_t(ctrl)].position;
    EXPECT_EQ(p, vec3(q[0], q[1], q[2]));
  }
  // The centre of a biquadratic patch: weights (1/4, 1/2, 1/4) in each direction.
  vec3 centre(0.0f);
  const float w[3] = {0.25f, 0.5f, 0.25f};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const auto& q = grid[size_t(j * 5 + i)].position;
      centre += w[i] * w[j] * vec3(q[0], q[1], q[2]);
    }
  const vec3 got = mesh.vertices[size_t(2 * 9 + 2)].position;
  EXPECT_NEAR(got.x, centre.x, 1e-4f);
  EXPECT_NEAR(got.y, centre.y, 1e-4f);
  EXPECT_NEAR(got.z, centre.z, 1e-4f);
  for (const auto& t : mesh.triangles)
    for (uint32_t i : t) EXPECT_LT(i, mesh.vertices.size());
}

// Two faces that share a border walked in opposite directions (the second face is the first
// one's right neighbour, its grid mirrored left to right) meet without cracks.
TEST(BspPatch, FacesSharingAReversedBorderGiveIdenticalVertices) {
  for (int level : {1, 3, 4, 5, 8}) {
    const std::vector<BspVertex> left = sheet(3, 5, 7);
    std::vector<BspVertex> right = sheet(3, 5, 8);
    // right's column 2 is left's column 2 (shared border), stored in reverse row order and with
    // the grid flipped vertically, so the border runs the other way.
    for (int r = 0; r < 5; ++r) right[size_t(r * 3 + 2)] = left[size_t((4 - r) * 3 + 2)];
    PatchMesh a, b;
    tessellate_patch(left, 3, 5, level, a);
    tessellate_patch(right, 3, 5, level, b);
    std::set<Key> from_a;
    const int columns = level + 1;  // one patch across
    for (int r = 0; r < 2 * level + 1; ++r)
      from_a.insert(key(a.vertices[size_t(r * columns + level)].position));
    int matched = 0;
    for (int r = 0; r < 2 * level + 1; ++r)
      matched += from_a.count(key(b.vertices[size_t(r * columns + level)].position)) ? 1 : 0;
    EXPECT_EQ(matched, 2 * level + 1) << "level " << level;
  }
}

// Inside one face, the border between two patches is one row of shared vertices: every
// triangle edge on it has a twin, so the mesh has boundary edges only on the face's outline.
TEST(BspPatch, OneFaceIsAClosedSheet) {
  const std::vector<BspVertex> grid = sheet(7, 5, 11);
  PatchMesh mesh;
  const int level = 5;
  tessellate_patch(grid, 7, 5, level, mesh);
  std::map<std::pair<Key, Key>, int> edges;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      Key p = key(mesh.vertices[t[size_t(e)]].position),
          q = key(mesh.vertices[t[size_t((e + 1) % 3)]].position);
      if (q < p) std::swap(p, q);
      ++edges[{p, q}];
    }
  int boundary = 0;
  for (const auto& [edge, count] : edges) {
    EXPECT_LE(count, 2);
    boundary += count == 1;
  }
  const int across = 3 * level, down = 2 * level;
  EXPECT_EQ(boundary, 2 * (across + down));
}

TEST(BspPatch, RejectsBadLevelsAndGrids) {
  const std::vector<BspVertex> grid = sheet(3, 3, 1);
  PatchMesh mesh;
  EXPECT_THROW(tessellate_patch(grid, 3, 3, 0, mesh), Error);
  EXPECT_THROW(tessellate_patch(grid, 3, 3, kMaxPatchLevel + 1, mesh), Error);
  EXPECT_THROW(tessellate_patch(grid, 3, 5, 2, mesh), Error);
}

}  // namespace
}  // namespace bounce::quake
