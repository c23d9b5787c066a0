#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

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

// The loop over a buffer (vector code, gathering from the tables) gives what the encoder gives one
// value at a time, outliers and a scale included, at every length (the vector loop's tail).
TEST(Srgb8Encoder, ABufferEncodesAsItsValuesOneByOne) {
  const Srgb8Encoder& e = srgb8_encoder();
  Pcg32 rng(11);
  std::vector<float> in(1037);
  for (float& v : in) v = 1.5f * std::pow(rng.next_float(), 2.0f) - 0.1f;
  in[3] = std::numeric_limits<float>::quiet_NaN();
  in[10] = std::numeric_limits<float>::infinity();
  in[11] = -std::numeric_limits<float>::infinity();
  in[12] = -0.0f;
  for (const float scale : {1.0f, 0.37f, 4.0f})
    for (const size_t n : {size_t(0), size_t(1), size_t(7), size_t(33), in.size()}) {
      std::vector<uint8_t> out(n, 0xAB);
      e.encode(in.data(), scale, out.data(), n);
      for (size_t i = 0; i < n; ++i)
        ASSERT_EQ(out[i], e.encode(in[i] * scale)) << i << " " << scale;
    }
}

}  // namespace
}  // namespace bounce
