// A texture's chain of box-filtered levels (build_texture_levels) and the lookup over a footprint
// (TextureView::sample(uv, width)): the levels' means by hand, level 0 alone for a point, the
// mean for a footprint as wide as the texture, and the finer level between.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/scene/texture.h"

namespace bounce {
namespace {

// A texture and its chain, kept together.
struct Chain {
  std::vector<vec3> texels;
  TextureView view;
};
Chain chain_of(int w, int h, const std::vector<vec3>& level0) {
  Chain c;
  c.texels.resize(texture_chain_texels(w, h));
  std::copy(level0.begin(), level0.end(), c.texels.begin());
  c.view = {c.texels.data(), w, h};
  build_texture_levels(c.view, c.texels.data());
  return c;
}

// Black and white texels in a checkerboard, `n` x `n`.
std::vector<vec3> checkerboard(int n) {
  std::vector<vec3> t(size_t(n) * size_t(n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) t[size_t(y * n + x)] = vec3(float((x + y) % 2));
  return t;
}

TEST(TextureLevels, ACheckerboardsLevelsAreGrey) {
  const Chain c = chain_of(8, 8, checkerboard(8));
  EXPECT_EQ(texture_chain_texels(8, 8), 64u + 16u + 4u + 1u);
  ASSERT_EQ(c.view.levels, 4);
  for (int k = 1; k < 4; ++k) {
    EXPECT_EQ(c.view.level_width(k), 8 >> k);
    for (int i = 0; i < (8 >> k) * (8 >> k); ++i)
      EXPECT_EQ(c.texels[size_t(c.view.level_offset[k] + i)], vec3(0.5f)) << k << " " << i;
  }
}

// An odd side's last texel takes three: 5 x 3 -> 2 x 1 -> 1 x 1.
TEST(TextureLevels, AnOddSidesLastTexelTakesThree) {
  std::vector<vec3> t;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) t.push_back(vec3(float(x), float(y), 1.0f));
  const Chain c = chain_of(5, 3, t);
  ASSERT_EQ(c.view.levels, 3);
  EXPECT_EQ(texture_chain_texels(5, 3), 15u + 2u + 1u);
  const vec3* level1 = c.texels.data() + c.view.level_offset[1];
  EXPECT_EQ(level1[0], vec3(0.5f, 1.0f, 1.0f));  // columns 0-1, rows 0-2
  EXPECT_EQ(level1[1], vec3(3.0f, 1.0f, 1.0f));  // columns 2-4
  EXPECT_EQ(c.texels[size_t(c.view.level_offset[2])], vec3(1.75f, 1.0f, 1.0f));
}

TEST(TextureLevels, APointReadsLevelZeroAndTheWholeTextureItsMean) {
  const Chain c = chain_of(8, 8, checkerboard(8));
  Pcg32 rng(3);
  for (int k = 0; k < 200; ++k) {
    const vec2 uv(rng.next_float() * 3.0f - 1.0f, rng.next_float() * 3.0f - 1.0f);
    EXPECT_EQ(c.view.sample(uv, 0.0f), c.view.sample(uv));
    // Narrower than a texel: still level 0.
    EXPECT_EQ(c.view.sample(uv, 0.5f / 8.0f), c.view.sample(uv));
    EXPECT_EQ(c.view.sample(uv, 1.0f), vec3(0.5f));
    EXPECT_EQ(c.view.sample(uv, 100.0f), vec3(0.5f));
    // Two texels wide: level 1, grey; the finer level between: below 2 texels level 0.
    EXPECT_EQ(c.view.sample(uv, 2.0f / 8.0f), vec3(0.5f));
    EXPECT_EQ(c.view.sample(uv, 1.9f / 8.0f), c.view.sample(uv));
    EXPECT_EQ(c.view.sample(uv, 3.9f / 8.0f), vec3(0.5f));
  }
}

// A footprint that is not a number (absurd texture coordinates per metre times a zero distance)
// reads level 0, an infinite one the last level: never outside the chain.
TEST(TextureLevels, AbsurdFootprintsStayInTheChain) {
  const Chain c = chain_of(8, 8, checkerboard(8));
  const vec2 uv(0.3f, 0.7f);
  EXPECT_EQ(c.view.sample(uv, std::numeric_limits<float>::quiet_NaN()), c.view.sample(uv));
  EXPECT_EQ(c.view.sample(uv, std::numeric_limits<float>::infinity()), vec3(0.5f));
  EXPECT_EQ(c.view.sample(uv, -1.0f), c.view.sample(uv));
}

// The level of detail's log2: exact at powers of two, piecewise linear between (at most 0.09
// off), never decreasing.
TEST(TextureLevels, CoarseLog2IsCloseToLog2) {
  for (int e = 0; e < 20; ++e) EXPECT_EQ(coarse_log2(float(1 << e)), float(e));
  float last = 0.0f;
  for (float x = 1.0f; x < 5000.0f; x *= 1.01f) {
    EXPECT_NEAR(coarse_log2(x), std::log2(x), 0.09f) << x;
    EXPECT_GE(coarse_log2(x), last);
    last = coarse_log2(x);
  }
}

}  // namespace
}  // namespace bounce
