// sRGB transfer functions and luminance: the one place PNG input and output convert colours.
#pragma once

#include <cmath>
#include <cstdint>

#include "bounce/core/lane.h"
#include "bounce/core/math.h"

namespace bounce {

// Linear -> sRGB-encoded value (IEC 61966-2-1 OETF); negative inputs stay on the linear segment.
BOUNCE_HD inline float srgb_encode(float linear) {
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// sRGB-encoded value -> linear (the exact inverse of srgb_encode).
inline float srgb_decode(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Relative luminance of a linear colour with Rec. 709 / sRGB primaries.
BOUNCE_HD inline float luminance(vec3 rgb) {
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

// Scales, clamps to [0, 1] and encodes one linear channel as an 8-bit sRGB value. NaN maps to 0
// so that a bad pixel shows as black instead of reaching an undefined float-to-int conversion.
BOUNCE_HD inline uint8_t srgb8_from_linear(float linear, float scale) {
  float v = linear * scale;
  if (!(v > 0.0f)) v = 0.0f;
  if (v > 1.0f) v = 1.0f;
  return static_cast<uint8_t>(std::lround(255.0f * srgb_encode(v)));
}

}  // namespace bounce

namespace bounce {

// srgb8_from_linear without pow: the 8-bit code of a linear value is the number of code
// boundaries (the linear values where the rounded code steps up) at or below it. A table over
// 8192 equal bins of [0, 1] gives the code at the bin's start; the bins are narrower than the
// closest two boundaries (1 / (255 * 12.92) apart, where the curve is steepest), so the value
// passes at most one more, and the lookup has no loop and no branch. Same result as
// srgb8_from_linear, several times faster.
class Srgb8Encoder {
 public:
  static constexpr int kBins = 8192;
  Srgb8Encoder();
  uint8_t encode(float linear) const {
    // (x > 0 fails for NaN too, which maps to 0. Selects as bit operations: with the ternary
    // operator GCC leaves the loop below scalar.)
    const float positive = pick(linear > 0.0f, linear, 0.0f);
    const float v = pick(positive < 1.0f, positive, 1.0f);
    const int32_t k = bin_code_[int(v * kBins)];
    return uint8_t(k + int32_t(boundaries_[k] <= v));
  }
  // out[i] = encode(in[i] * scale) for n values (out overlapping neither `in` nor the encoder).
  void encode(const float* in, float scale, uint8_t* out, size_t n) const {
    BOUNCE_IVDEP
    for (size_t i = 0; i < n; ++i) out[i] = encode(in[i] * scale);
  }

 private:
  float boundaries_[256];  // boundaries_[k]: smallest linear value whose code exceeds k
  // The code of each bin's lower end, 32 bits wide: GCC gathers 32-bit entries only, and with
  // them (and the boundaries) gathered eight at a time encode's loop vectorises; over a table of
  // bytes it stayed scalar, 2.6 times slower (docs/benchmarks.md, stop 56).
  int32_t bin_code_[kBins + 1];
};

const Srgb8Encoder& srgb8_encoder();

}  // namespace bounce
