#include "bounce/core/color.h"

#include <limits>

#include "bounce/core/error.h"

namespace bounce {

Srgb8Encoder::Srgb8Encoder() {
  // Find each boundary by bisection on srgb8_from_linear itself, so the two agree exactly.
  for (int k = 0; k < 255; ++k) {
    float lo = 0.0f, hi = 1.0f;  // code(lo) <= k < code(hi)
    for (int i = 0; i < 64; ++i) {
      const float mid = 0.5f * (lo + hi);
      if (mid == lo || mid == hi) break;
      (srgb8_from_linear(mid, 1.0f) > k ? hi : lo) = mid;
    }
    boundaries_[k] = hi;
  }
  boundaries_[255] = std::numeric_limits<float>::infinity();
  for (int b = 0; b <= kBins; ++b) bin_code_[b] = srgb8_from_linear(float(b) / kBins, 1.0f);
  // encode() steps over at most one boundary past its bin's start.
  for (int b = 0; b < kBins; ++b)
    if (bin_code_[b] < 255 && boundaries_[bin_code_[b] + 1] < float(b + 1) / kBins)
      fail("sRGB encoder: bin {} holds two code boundaries", b);
}

const Srgb8Encoder& srgb8_encoder() {
  static const Srgb8Encoder encoder;
  return encoder;
}

}  // namespace bounce
