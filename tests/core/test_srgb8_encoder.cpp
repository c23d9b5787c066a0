#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bounce/core/color.h"
#include "bounce/core/rng.h"

namespace bounce {
namespace {

TEST(Srgb8Encoder, AgreesWithTheDirectFormulaEverywhere) {
  const Srgb8Encoder& e = srgb8_encoder();
  // Every float in [0, 1] from a dense sweep, values around each code boundary, and outliers.
  for (int i = 0; i <= 1 << 20; ++i) {
    const float v = float(i) / float(1 << 20);
    ASSERT_EQ(e.encode(v), srgb8_from_linear(v, 1.0f)) << v;
  }
  Pcg32 rng(5);
  for (int i = 0; i < 200000; ++i) {
    const float v = std::pow(rng.next_float(), 3.0f);
    ASSERT_EQ(e.encode(v), srgb8_from_linear(v, 1.0f)) << v;
  }
  for (float v : {-1.0f, 0.0f, 1.0f, 2.0f, 1e30f, std::numeric_limits<float>::infinity(),
                  std::numeric_limits<float>::quiet_NaN()})
    EXPECT_EQ(e.encode(v), srgb8_from_linear(v, 1.0f)) << v;
  EXPECT_EQ(e.encode(1.0f), 255);
  EXPECT_EQ(e.encode(0.5f), 188);  // 255 * 0.7354 = 187.5...
}

}  // namespace
}  // namespace bounce
