#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/rng.h"
#include "bounce/render/photon_hash_grid.h"

namespace bounce {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::vector<vec3> random_points(size_t n, vec3 lo, vec3 hi, uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<vec3> points(n);
  for (vec3& p : points)
    p = lo + (hi - lo) * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  return points;
}

// Visited indices in visit order.
std::vector<uint32_t> gather(const PhotonHashGrid& grid, vec3 x, float r) {
  std::vector<uint32_t> out;
  grid.for_each_within(x, r, [&](uint32_t i) { out.push_back(i); });
  return out;
}

// Indices within r of x by brute force, ascending; the same distance test as the grid.
std::vector<uint32_t> brute_force(const std::vector<vec3>& points, vec3 x, float r) {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < points.size(); ++i)
    if (is_finite(points[i]) && within_radius(points[i], x, r * r)) out.push_back(uint32_t(i));
  return out;
}

// Checks one gather against brute force as sets, and that no index comes twice. Returns the
// number of points found.
size_t expect_matches(const PhotonHashGrid& grid, const std::vector<vec3>& points, vec3 x,
                      float r) {
  std::vector<uint32_t> got = gather(grid, x, r);
  std::sort(got.begin(), got.end());
  EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end())
      << "duplicate at (" << x.x << ", " << x.y << ", " << x.z << ") r " << r;
  const std::vector<uint32_t> want = brute_force(points, x, r);
  EXPECT_EQ(got, want) << "query (" << x.x << ", " << x.y << ", " << x.z << ") r " << r;
  return want.size();
}

TEST(PhotonHashGrid, CellCoordinateIsAClampedFloor) {
  using V = PhotonHashGridView;
  EXPECT_EQ(V::cell_coord(0.0f), 0);
  EXPECT_EQ(V::cell_coord(-0.0f), 0);
  EXPECT_EQ(V::cell_coord(0.999999f), 0);
  EXPECT_EQ(V::cell_coord(1.0f), 1);
  EXPECT_EQ(V::cell_coord(-1e-7f), -1);
  EXPECT_EQ(V::cell_coord(-1.0f), -1);
  EXPECT_EQ(V::cell_coord(-1.5f), -2);
  EXPECT_EQ(V::cell_coord(1234567.5f), 1234567);
  EXPECT_EQ(V::cell_coord(-1234567.5f), -1234568);
  EXPECT_EQ(V::cell_coord(1e30f), 2097152);
  EXPECT_EQ(V::cell_coord(-kInf), -2097152);
  EXPECT_EQ(V::cell_coord(kNaN), -2097152);
}

TEST(PhotonHashGrid, MatchesBruteForceForSeveralRadii) {
  const std::vector<vec3> points = random_points(4000, vec3(0.0f), vec3(1.0f), 7);
  Pcg32 rng(11);
  for (float build_radius : {0.01f, 0.05f, 0.2f}) {
    PhotonHashGrid grid;
    grid.build(points, build_radius);
    EXPECT_EQ(grid.size(), points.size());
    EXPECT_EQ(grid.radius(), build_radius);
    EXPECT_EQ(grid.table_size(), 8192u);  // power of two >= 2 * 4000
    for (float scale : {1.0f, 0.7f, 0.25f}) {
      const float r = build_radius * scale;
      size_t found = 0;
      for (int q = 0; q < 300; ++q) {
        // Queries also a little outside the points' box, and some exactly on a point.
        const vec3 x = q % 5 == 0 ? points[rng.next_below(uint32_t(points.size()))]
                                  : vec3(-0.1f) + 1.2f * vec3(rng.next_float(), rng.next_float(),
                                                              rng.next_float());
        found += expect_matches(grid, points, x, r);
      }
      // Every fifth query sits on a point and finds at least that one.
      EXPECT_GE(found, 60u) << "build radius " << build_radius << " scale " << scale;
    }
  }
}

TEST(PhotonHashGrid, MatchesBruteForceOnCellBoundaries) {
  // Radius 0.5: cells are 1 wide, so integer coordinates lie on cell faces, and half-integer
  // steps put points at exactly the gather radius (excluded: distance < radius). All exact.
  std::vector<vec3> points;
  for (int z = -6; z <= 6; ++z)
    for (int y = -6; y <= 6; ++y)
      for (int x = -6; x <= 6; ++x) points.push_back(vec3(float(x), float(y), float(z)) * 0.5f);
  PhotonHashGrid grid;
  grid.build(points, 0.5f);
  size_t found = 0;
  for (int z = -7; z <= 7; ++z)
    for (int y = -7; y <= 7; ++y)
      for (int x = -7; x <= 7; ++x) {
        const vec3 q = vec3(float(x), float(y), float(z)) * 0.25f;
        for (float r : {0.5f, 0.25f, 0.5f - 1e-6f, 0.25f + 1e-6f})
          found += expect_matches(grid, points, q, r);
      }
  EXPECT_GT(found, 0u);
  // At a lattice point only the point itself is closer than 0.5 (neighbours are exactly 0.5).
  EXPECT_EQ(gather(grid, vec3(1.0f, -0.5f, 0.0f), 0.5f).size(), 1u);
  // Midway between two lattice points along x both are at 0.25: strictly inside 0.25 + eps only.
  EXPECT_EQ(gather(grid, vec3(0.25f, 0.0f, 0.0f), 0.25f).size(), 0u);
  EXPECT_EQ(gather(grid, vec3(0.25f, 0.0f, 0.0f), 0.2500001f).size(), 2u);
}

TEST(PhotonHashGrid, NoDuplicatesWhenCellsShareASlot) {
  // Many more occupied cells than slots (1024): a query's 8 cells often collide in the table.
  const std::vector<vec3> points = random_points(300, vec3(0.0f), vec3(100.0f), 3);
  PhotonHashGrid grid;
  grid.build(points, 2.0f);
  ASSERT_EQ(grid.table_size(), 1024u);
  const PhotonHashGridView view = grid.view();
  Pcg32 rng(5);
  int colliding_queries = 0;
  for (int q = 0; q < 20000; ++q) {
    const vec3 x = 100.0f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
    ivec3 lo, hi;
    view.cell_range(x, 2.0f, lo, hi);
    std::vector<uint32_t> slots;
    for (int cz = lo.z; cz <= hi.z; ++cz)
      for (int cy = lo.y; cy <= hi.y; ++cy)
        for (int cx = lo.x; cx <= hi.x; ++cx) slots.push_back(view.slot(ivec3(cx, cy, cz)));
    std::sort(slots.begin(), slots.end());
    const bool collides = std::adjacent_find(slots.begin(), slots.end()) != slots.end();
    colliding_queries += collides;
    // Checking the colliding queries (and a sample of the rest) keeps the test quick.
    if (collides || q % 20 == 0) expect_matches(grid, points, x, 2.0f);
  }
  EXPECT_GT(colliding_queries, 20);  // the case under test did occur
}

TEST(PhotonHashGrid, DeterministicArraysAndOrder) {
  const std::vector<vec3> points = random_points(20000, vec3(-1.0f), vec3(1.0f), 21);
  const std::vector<vec3> queries = random_points(200, vec3(-1.0f), vec3(1.0f), 22);
  auto snapshot = [&](int threads) {
    ThreadLimit limit(threads);
    PhotonHashGrid grid;
    grid.build(points, 0.05f);
    std::vector<uint32_t> order;
    for (vec3 q : queries) grid.for_each_within(q, 0.05f, [&](uint32_t i) { order.push_back(i); });
    return std::make_tuple(
        std::vector<uint32_t>(grid.cell_start().begin(), grid.cell_start().end()),
        std::vector<uint32_t>(grid.indices().begin(), grid.indices().end()),
        std::vector<vec3>(grid.sorted_points().begin(), grid.sorted_points().end()), order);
  };
  const auto one = snapshot(1);
  const auto two = snapshot(2);
  const auto again = snapshot(0);
  EXPECT_TRUE(one == two);
  EXPECT_TRUE(one == again);
  EXPECT_GT(std::get<3>(one).size(), 200u);

  // Within a slot, points keep their index order; the sorted positions match the indices.
  const auto& [start, index, sorted, order] = one;
  for (size_t s = 0; s + 1 < start.size(); ++s)
    for (uint32_t k = start[s] + 1; k < start[s + 1]; ++k) EXPECT_LT(index[k - 1], index[k]);
  for (size_t k = 0; k < index.size(); ++k) EXPECT_EQ(sorted[k], points[index[k]]);
}

TEST(PhotonHashGrid, ReusedGridRebuildsCleanly) {
  const std::vector<vec3> big = random_points(5000, vec3(0.0f), vec3(1.0f), 31);
  const std::vector<vec3> small = random_points(100, vec3(0.0f), vec3(1.0f), 32);
  PhotonHashGrid grid;
  grid.build(big, 0.1f);
  grid.build(small, 0.2f);
  EXPECT_EQ(grid.size(), 100u);
  EXPECT_EQ(grid.table_size(), 1024u);
  PhotonHashGrid fresh;
  fresh.build(small, 0.2f);
  EXPECT_TRUE(std::ranges::equal(grid.cell_start(), fresh.cell_start()));
  EXPECT_TRUE(std::ranges::equal(grid.indices(), fresh.indices()));
  for (vec3 q : random_points(50, vec3(0.0f), vec3(1.0f), 33)) expect_matches(grid, small, q, 0.2f);
  // A copy answers the same queries after the original is rebuilt (no shared pointers).
  const PhotonHashGrid copy = grid;
  grid.build(big, 0.1f);
  for (vec3 q : random_points(50, vec3(0.0f), vec3(1.0f), 34)) expect_matches(copy, small, q, 0.2f);
}

TEST(PhotonHashGrid, EmptyGrid) {
  PhotonHashGrid unbuilt;
  EXPECT_EQ(unbuilt.size(), 0u);
  EXPECT_EQ(unbuilt.radius(), 0.0f);
  EXPECT_TRUE(gather(unbuilt, vec3(0.0f), 0.0f).empty());

  PhotonHashGrid grid;
  grid.build({}, 0.1f);
  EXPECT_EQ(grid.size(), 0u);
  EXPECT_EQ(grid.radius(), 0.1f);
  EXPECT_EQ(grid.table_size(), 1024u);
  EXPECT_TRUE(gather(grid, vec3(0.0f), 0.1f).empty());
}

TEST(PhotonHashGrid, AllPointsIdentical) {
  const std::vector<vec3> points(1000, vec3(0.3f, -2.0f, 7.5f));
  PhotonHashGrid grid;
  grid.build(points, 0.01f);
  std::vector<uint32_t> all(points.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
  EXPECT_EQ(gather(grid, points[0], 0.01f), all);  // index order: one cell
  EXPECT_EQ(gather(grid, points[0] + vec3(0.009f, 0.0f, 0.0f), 0.01f), all);
  EXPECT_TRUE(gather(grid, points[0] + vec3(0.0f, 0.011f, 0.0f), 0.01f).empty());
  EXPECT_TRUE(gather(grid, points[0] + vec3(0.0f, 0.0f, 0.0051f), 0.005f).empty());
}

TEST(PhotonHashGrid, HugeCoordinates) {
  // Around 1e7 floats are 1 apart, so these points sit on integers: many share positions.
  std::vector<vec3> points = random_points(3000, vec3(1e7f), vec3(1e7f + 40.0f), 41);
  const std::vector<vec3> negative = random_points(1000, vec3(-1e7f - 40.0f), vec3(-1e7f), 42);
  points.insert(points.end(), negative.begin(), negative.end());
  // Far beyond the clamped cell range, and at the top of the float range.
  for (float c : {1e30f, -1e30f, 3e38f, -3e38f}) points.push_back(vec3(c, 0.5f, c));
  // Radius 4: cell coordinates near 1e7 / 8 stay below the clamp (2^21); radius 1.5: they are
  // clamped, and the points around +-1e7 share the boundary cells.
  PhotonHashGrid grid;
  Pcg32 rng(43);
  for (float build_radius : {4.0f, 1.5f}) {
    grid.build(points, build_radius);
    EXPECT_EQ(grid.size(), points.size());
    size_t found = 0;
    for (int q = 0; q < 300; ++q) {
      const vec3 x =
          points[rng.next_below(uint32_t(points.size()))] +
          (vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f - 1.0f) * build_radius;
      for (float scale : {1.0f, 0.6f, 0.2f})
        found += expect_matches(grid, points, x, build_radius * scale);
    }
    EXPECT_GT(found, 300u);
  }
  for (float c : {1e30f, -1e30f, 3e38f, -3e38f}) {
    const std::vector<uint32_t> got = gather(grid, vec3(c, 0.5f, c), 1.0f);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(points[got[0]], vec3(c, 0.5f, c));
  }

  // Small cells far from the origin: coordinates/cell exceed the clamp, points still found.
  PhotonHashGrid fine;
  fine.build(points, 1e-3f);
  for (int q = 0; q < 200; ++q) {
    const vec3 x = points[rng.next_below(uint32_t(points.size()))];
    EXPECT_GE(expect_matches(fine, points, x, 1e-3f), 1u);
  }
}

TEST(PhotonHashGrid, NonFinitePointsAreSkipped) {
  std::vector<vec3> points = random_points(500, vec3(0.0f), vec3(1.0f), 51);
  points[17] = vec3(kNaN, 0.5f, 0.5f);
  points[200] = vec3(0.5f, 0.5f, kNaN);
  points[300] = vec3(kInf, 0.5f, 0.5f);
  points[301] = vec3(0.5f, -kInf, 0.5f);
  PhotonHashGrid grid;
  grid.build(points, 0.3f);
  EXPECT_EQ(grid.size(), points.size() - 4);
  for (vec3 q : random_points(200, vec3(0.0f), vec3(1.0f), 52)) {
    for (uint32_t i : gather(grid, q, 0.3f)) {
      EXPECT_NE(i, 17u);
      EXPECT_NE(i, 200u);
      EXPECT_NE(i, 300u);
      EXPECT_NE(i, 301u);
    }
    expect_matches(grid, points, q, 0.3f);
  }
  // Non-finite query points and radii find nothing (and do not crash).
  EXPECT_TRUE(gather(grid, vec3(kNaN, 0.5f, 0.5f), 0.3f).empty());
  EXPECT_TRUE(gather(grid, vec3(kInf, 0.5f, 0.5f), 0.3f).empty());
  EXPECT_TRUE(gather(grid, vec3(0.5f), kNaN).empty());
  EXPECT_TRUE(gather(grid, vec3(0.5f), -0.1f).empty());

  // Only non-finite points: an empty grid.
  const std::vector<vec3> bad(10, vec3(kNaN));
  grid.build(bad, 0.3f);
  EXPECT_EQ(grid.size(), 0u);
  EXPECT_TRUE(gather(grid, vec3(0.0f), 0.3f).empty());
}

TEST(PhotonHashGrid, BadRadiusThrows) {
  const std::vector<vec3> points(3, vec3(0.0f));
  PhotonHashGrid grid;
  for (float r : {0.0f, -0.0f, -1.0f, kNaN, kInf, -kInf, 1e-45f}) {
    EXPECT_THROW(grid.build(points, r), Error) << r;
  }
  try {
    grid.build(points, -2.0f);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("-2"), std::string::npos);
  }
  // A failed build leaves the previous grid untouched (validation comes first).
  grid.build(points, 1.0f);
  EXPECT_THROW(grid.build(points, 0.0f), Error);
  EXPECT_EQ(gather(grid, vec3(0.0f), 1.0f).size(), 3u);
}

}  // namespace
}  // namespace bounce
