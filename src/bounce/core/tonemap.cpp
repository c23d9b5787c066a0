#include "bounce/core/tonemap.h"

#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/parallel.h"

namespace bounce {

void tonemap_srgb8(const Image& linear, float exposure_ev, std::vector<uint8_t>& out) {
  const float scale = std::exp2(exposure_ev);
  const Srgb8Encoder& encoder = srgb8_encoder();
  out.resize(linear.pixel_count() * 3);
  parallel_for(
      linear.pixel_count(),
      [&](size_t i) {
        const vec3 c = linear.pixels()[i] * scale;
        for (int k = 0; k < 3; ++k) out[3 * i + k] = encoder.encode(c[k]);
      },
      4096);
}

}  // namespace bounce
