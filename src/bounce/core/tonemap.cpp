#include "bounce/core/tonemap.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/parallel.h"

namespace bounce {

void tonemap_srgb8(const Image& linear, float exposure_ev, std::vector<uint8_t>& out) {
  const float scale = std::exp2(exposure_ev);
  const Srgb8Encoder& encoder = srgb8_encoder();
  const size_t n = linear.pixel_count() * 3;
  out.resize(n);
  if (n == 0) return;
  const float* in = &linear.pixels()[0].x;  // vec3 is three packed floats
  constexpr size_t kChunk = 3 * 4096;
  parallel_for((n + kChunk - 1) / kChunk,
               [&](size_t c) {
                 const size_t begin = c * kChunk;
                 encoder.encode(in + begin, scale, out.data() + begin, std::min(kChunk, n - begin));
               },
               1);
}

}  // namespace bounce
