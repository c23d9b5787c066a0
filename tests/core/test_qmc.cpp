#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"

namespace bounce {
namespace {

TEST(Qmc, ReverseBitsKnownValues) {
  EXPECT_EQ(reverse_bits(1u), 0x80000000u);
  EXPECT_EQ(reverse_bits(0x80000000u), 1u);
  EXPECT_EQ(reverse_bits(0x0000F00Fu), 0xF00F0000u);
  EXPECT_EQ(reverse_bits(0x12345678u), 0x1E6A2C48u);
}

TEST(Qmc, VanDerCorputKnownValues) {
  const float expected[] = {0.0f, 0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(radical_inverse2(i), expected[i]) << i;
  // The general radical inverse agrees in base 2 and gives the base-3 sequence.
  for (uint32_t i = 0; i < 1000; ++i)
    EXPECT_NEAR(radical_inverse(2, i), radical_inverse2(i), 1e-7f);
  EXPECT_FLOAT_EQ(radical_inverse(3, 1), 1.0f / 3.0f);
  EXPECT_FLOAT_EQ(radical_inverse(3, 5), 2.0f / 3.0f + 1.0f / 9.0f);  // 5 = 12 in base 3
}

TEST(Qmc, HaltonUsesPrimeBases) {
  EXPECT_FLOAT_EQ(halton(0, 3), 0.75f);
  EXPECT_FLOAT_EQ(halton(1, 2), 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(halton(2, 1), 0.2f);
  EXPECT_FLOAT_EQ(halton(2, 7), 2.0f / 5.0f + 1.0f / 25.0f);  // 7 = 12 in base 5
}

TEST(Qmc, HammersleyKnownValues) {
  EXPECT_EQ(hammersley(0, 4), vec2(0.0f, 0.0f));
  EXPECT_EQ(hammersley(1, 4), vec2(0.25f, 0.5f));
  EXPECT_EQ(hammersley(2, 4), vec2(0.5f, 0.25f));
  EXPECT_EQ(hammersley(3, 4), vec2(0.75f, 0.75f));
}

// A (0, m, 2)-net in base 2: every elementary interval of area 1/N holds exactly one point.
void expect_elementary_stratification(const std::vector<vec2>& points) {
  const uint32_t n = uint32_t(points.size());
  uint32_t m = 0;
  while ((1u << m) < n) ++m;
  ASSERT_EQ(1u << m, n);
  for (uint32_t kx = 0; kx <= m; ++kx) {
    const uint32_t cx = 1u << kx, cy = 1u << (m - kx);
    std::set<uint32_t> cells;
    for (vec2 p : points) cells.insert(uint32_t(p.x * cx) * cy + uint32_t(p.y * cy));
    EXPECT_EQ(cells.size(), n) << "intervals " << cx << "x" << cy;
  }
}

TEST(Qmc, HammersleyIsStratifiedInEveryElementaryInterval) {
  for (uint32_t n : {16u, 64u, 256u}) {
    std::vector<vec2> points;
    for (uint32_t i = 0; i < n; ++i) points.push_back(hammersley(i, n));
    expect_elementary_stratification(points);
  }
}

// The screen lattice: in every 4x4 and 8x8 block of pixels the points keep apart (the closest
// two 0.40 and 0.62 of the spacing 1/block of an even spread; independent uniform points come
// within about 0.1 of it), and the first coordinate alone leaves no gap over twice the even
// 1/block^2 (1.27 and 1.65 times).
TEST(Qmc, ScreenLatticeSpreadsEveryBlockOfPixels) {
  const auto wrap = [](float d) { return std::min(std::fabs(d), 1.0f - std::fabs(d)); };
  for (uint32_t block : {4u, 8u})
    for (uint32_t y0 = 0; y0 < 64; y0 += block)
      for (uint32_t x0 = 1000; x0 < 1064; x0 += block) {
        std::vector<vec2> points;
        std::vector<float> first;
        for (uint32_t y = y0; y < y0 + block; ++y)
          for (uint32_t x = x0; x < x0 + block; ++x) {
            points.push_back({bits_to_unit_float(screen_lattice_x(x, y)),
                              bits_to_unit_float(screen_lattice_y(x, y))});
            first.push_back(points.back().x);
          }
        float closest = 1.0f;
        for (size_t a = 0; a < points.size(); ++a)
          for (size_t b = a + 1; b < points.size(); ++b)
            closest = std::min(closest, std::hypot(wrap(points[a].x - points[b].x),
                                                   wrap(points[a].y - points[b].y)));
        EXPECT_GT(closest * float(block), 0.35f) << block << " at " << x0 << "," << y0;
        std::sort(first.begin(), first.end());
        float gap = 1.0f - first.back() + first.front();
        for (size_t k = 1; k < first.size(); ++k) gap = std::max(gap, first[k] - first[k - 1]);
        EXPECT_LT(gap * float(block * block), 2.0f) << block << " at " << x0 << "," << y0;
      }
}

TEST(Qmc, SobolKnownValuesAndStratification) {
  // The first points of Sobol' dimensions 0 and 1.
  const vec2 expected[] = {{0.0f, 0.0f},     {0.5f, 0.5f},     {0.25f, 0.75f},   {0.75f, 0.25f},
                           {0.125f, 0.625f}, {0.625f, 0.125f}, {0.375f, 0.375f}, {0.875f, 0.875f}};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(sobol2(i), expected[i]) << i;
  for (uint32_t n : {16u, 128u, 1024u}) {
    std::vector<vec2> points;
    for (uint32_t i = 0; i < n; ++i) points.push_back(sobol2(i));
    expect_elementary_stratification(points);
    // A (0,2)-sequence: the next block of n points is a net too.
    points.clear();
    for (uint32_t i = n; i < 2 * n; ++i) points.push_back(sobol2(i));
    expect_elementary_stratification(points);
  }
}

TEST(Rng, TeaMatchesReferenceAndIsInUnitInterval) {
  // TEA with 16 rounds of (0, 0), computed by hand from the round function.
  uint32_t v0 = 0, v1 = 0, sum = 0;
  for (int i = 0; i < 16; ++i) {
    sum += 0x9E3779B9u;
    v0 += ((v1 << 4) + 0xA341316Cu) ^ (v1 + sum) ^ ((v1 >> 5) + 0xC8013EA4u);
    v1 += ((v0 << 4) + 0xAD90777Du) ^ (v0 + sum) ^ ((v0 >> 5) + 0x7E95761Eu);
  }
  EXPECT_EQ(tea<16>(0, 0), uvec2(v0, v1));
  EXPECT_NE(tea<16>(0, 0), tea<16>(1, 0));
  TeaRng rng = TeaRng::for_path(7);
  double sum_u = 0.0;
  for (int i = 0; i < 10000; ++i) {
    const vec2 u = rng.next2();
    ASSERT_GE(u.x, 0.0f);
    ASSERT_LT(u.x, 1.0f);
    ASSERT_GE(u.y, 0.0f);
    ASSERT_LT(u.y, 1.0f);
    sum_u += u.x + u.y;
  }
  EXPECT_NEAR(sum_u / 20000.0, 0.5, 0.01);
}

TEST(Rng, PcgIsDeterministicAndUniform) {
  Pcg32 a(42), b(42), c(43);
  EXPECT_EQ(a.next_u32(), b.next_u32());
  EXPECT_NE(Pcg32(42).next_u32(), c.next_u32());
  Pcg32 r(1);
  std::vector<int> counts(10, 0);
  for (int i = 0; i < 100000; ++i) ++counts[r.next_below(10)];
  for (int k : counts) EXPECT_NEAR(k, 10000, 500);
}

}  // namespace
}  // namespace bounce
