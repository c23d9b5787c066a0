// Half-precision words (core/half_float.h): rounding to nearest even as IEEE binary16 does, the
// clamp and the flush at the ends of the range, exact decoding, and two halves in a word.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "bounce/core/half_float.h"
#include "bounce/core/rng.h"

namespace bounce {
namespace {

// The half nearest f with ties to even, by its definition: the normal halves of f's binade
// are spaced 2^(e - 10) apart.
float nearest_half(float f) {
  const float a = std::fabs(f);
  int e = 0;
  std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1)
  const float spacing = std::ldexp(1.0f, e - 11);
  const float q = a / spacing;  // exact: a power-of-two scale
  float r = std::nearbyint(q);  // the default rounding mode: ties to even
  return std::copysign(r * spacing, f);
}

TEST(HalfFloat, RoundsToTheNearestHalfTiesToEven) {
  Pcg32 rng(7);
  for (int k = 0; k < 200000; ++k) {
    // Magnitudes across the normal halves' range, both signs.
    const float f = (rng.next_float() < 0.5f ? -1.0f : 1.0f) *
                    std::ldexp(1.0f + rng.next_float(), int(rng.next_float() * 30.0f) - 14);
    if (std::fabs(f) >= 65504.0f) continue;
    const float h = half_float(half_bits(f));
    ASSERT_EQ(h, nearest_half(f)) << f;
    // Within half a spacing: 2^-11 of the value.
    ASSERT_LE(std::fabs(h - f), std::ldexp(std::fabs(f), -11)) << f;
  }
  // Ties: 1 + 2^-11 lies halfway between 1 and 1 + 2^-10 and goes to 1 (even); 1 + 3 2^-11 goes
  // up to 1 + 2^-9.
  EXPECT_EQ(half_float(half_bits(1.0f + std::ldexp(1.0f, -11))), 1.0f);
  EXPECT_EQ(half_float(half_bits(1.0f + 3.0f * std::ldexp(1.0f, -11))),
            1.0f + std::ldexp(1.0f, -9));
  // A carry into the exponent: just under 2 rounds to 2.
  EXPECT_EQ(half_float(half_bits(std::nextafter(2.0f, 0.0f))), 2.0f);
}

TEST(HalfFloat, RepresentableValuesRoundTripExactly) {
  for (const float f : {0.0f, 1.0f, -1.0f, 0.5f, 0.75f, 1024.0f, 65504.0f, -65504.0f,
                        std::ldexp(1.0f, -14), 3.140625f})
    EXPECT_EQ(half_float(half_bits(f)), f) << f;
  EXPECT_EQ(half_bits(1.0f), 0x3C00u);  // IEEE binary16's bits
  EXPECT_EQ(half_bits(-2.0f), 0xC000u);
  EXPECT_EQ(half_bits(65504.0f), 0x7BFFu);
}

TEST(HalfFloat, ClampsLargeValuesAndFlushesTinyOnes) {
  EXPECT_EQ(half_float(half_bits(1e6f)), 65504.0f);
  EXPECT_EQ(half_float(half_bits(-1e30f)), -65504.0f);
  EXPECT_EQ(half_float(half_bits(std::numeric_limits<float>::infinity())), 65504.0f);
  EXPECT_EQ(half_float(half_bits(1e-6f)), 0.0f);
  EXPECT_EQ(half_float(half_bits(std::nextafter(std::ldexp(1.0f, -14), 0.0f))), 0.0f);
  EXPECT_TRUE(std::signbit(half_float(half_bits(-1e-6f))));  // a signed zero
}

TEST(HalfFloat, TwoHalvesShareAWord) {
  const uint32_t w = pack_halves(0.25f, -3.5f);
  EXPECT_EQ(low_half(w), 0.25f);
  EXPECT_EQ(high_half(w), -3.5f);
  EXPECT_EQ(w, half_bits(0.25f) | (half_bits(-3.5f) << 16));
}

}  // namespace
}  // namespace bounce
