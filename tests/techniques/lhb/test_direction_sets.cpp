// Direction sets of the layered hit buffers: the counts of seed 001 section 3, unit length, and
// the constant-time nearest lookup against brute force on many random directions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bounce/core/error.h"
#include "bounce/techniques/lhb/direction_sets.h"

namespace bounce {
namespace {

std::vector<DirectionSet> all_sets() {
  std::vector<DirectionSet> sets;
  for (int level = 0; level <= 2; ++level) {
    sets.push_back(DirectionSet::octahedron(level));
    sets.push_back(DirectionSet::icosahedron(level));
    sets.push_back(DirectionSet::tetrahedron(level));
  }
  sets.push_back(DirectionSet::tetrahedron(3));
  for (int n : {1, 7, 144, 256, 320}) sets.push_back(DirectionSet::halton(n));
  for (int l : {1, 4, 9}) sets.push_back(DirectionSet::uv_grid(l));
  return sets;
}

vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> g;
  for (;;) {
    const vec3 v(g(rng), g(rng), g(rng));
    if (glm::length(v) > 1e-3f) return glm::normalize(v);
  }
}

TEST(DirectionSets, CountsFollowTheSeed) {
  EXPECT_EQ(DirectionSet::octahedron(0).size(), 8);
  EXPECT_EQ(DirectionSet::octahedron(1).size(), 32);
  EXPECT_EQ(DirectionSet::octahedron(2).size(), 128);
  EXPECT_EQ(DirectionSet::icosahedron(0).size(), 20);
  EXPECT_EQ(DirectionSet::icosahedron(1).size(), 80);
  EXPECT_EQ(DirectionSet::icosahedron(2).size(), 320);
  EXPECT_EQ(DirectionSet::tetrahedron(0).size(), 4);
  EXPECT_EQ(DirectionSet::tetrahedron(2).size(), 64);
  EXPECT_EQ(DirectionSet::halton(144).size(), 144);
  EXPECT_EQ(DirectionSet::uv_grid(8).size(), 256);  // 4 L^2
  EXPECT_EQ(DirectionSet::make(DirectionKind::kIcosahedron, 300).size(), 320);
  EXPECT_EQ(DirectionSet::make(DirectionKind::kOctahedron, 32).size(), 32);
  EXPECT_EQ(DirectionSet::make(DirectionKind::kHalton, 250).size(), 250);
}

TEST(DirectionSets, UnitAndBalanced) {
  for (const DirectionSet& set : all_sets()) {
    vec3 sum(0.0f);
    for (const vec3& d : set.directions()) {
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f) << set.name();
      sum += d;
    }
    // The solids and the UV grid are symmetric: their directions sum to zero.
    if (set.name().rfind("halton", 0) != 0) {
      EXPECT_LT(glm::length(sum), 1e-3f * float(set.size())) << set.name();
    }
  }
}

TEST(DirectionSets, IcosahedronCentroidsAreDistinctAndEvenlySpaced) {
  const DirectionSet set = DirectionSet::icosahedron(0);
  // Level 0: the dodecahedron's vertices; each has its three nearest neighbours at
  // acos(sqrt(5)/3) = 41.81 degrees.
  for (int i = 0; i < set.size(); ++i) {
    float best = -2.0f;
    for (int j = 0; j < set.size(); ++j)
      if (j != i) best = std::max(best, glm::dot(set.directions()[i], set.directions()[j]));
    EXPECT_NEAR(best, std::sqrt(5.0f) / 3.0f, 1e-5f);
  }
}

TEST(DirectionSets, LookupEqualsBruteForce) {
  std::mt19937 rng(12);
  for (const DirectionSet& set : all_sets()) {
    const DirectionSetView view = set.view();
    for (int k = 0; k < 20000; ++k) {
      const vec3 q = random_direction(rng);
      ASSERT_EQ(view.nearest(q), set.nearest_brute_force(q)) << set.name() << " query " << k;
    }
    // The set's own directions and the octahedral grid's seams (axes, folds, poles).
    for (const vec3& d : set.directions()) ASSERT_EQ(set.nearest(d), set.nearest_brute_force(d));
    for (vec3 q : {vec3(1, 0, 0), vec3(0, -1, 0), vec3(0, 0, -1), vec3(1, 1, 0), vec3(-1, 0, -1)}) {
      q = glm::normalize(q);
      EXPECT_EQ(set.nearest(q), set.nearest_brute_force(q)) << set.name();
    }
    // Bounded work: far fewer candidates than directions once the set is large.
    if (set.size() >= 128) {
      EXPECT_LT(set.max_candidates(), set.size() / 4) << set.name();
    }
  }
}

TEST(DirectionSets, BadInputIsAnError) {
  EXPECT_THROW(DirectionSet::icosahedron(9), Error);
  EXPECT_THROW(DirectionSet::halton(0), Error);
  EXPECT_THROW(DirectionSet::uv_grid(0), Error);
  EXPECT_THROW(DirectionSet::from_directions({}, "empty"), Error);
  EXPECT_THROW(DirectionSet::from_directions({vec3(0.0f)}, "zero"), Error);
}

}  // namespace
}  // namespace bounce
