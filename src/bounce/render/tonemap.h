// The tone-map stage: exposure, then the sRGB curve, to 8 bits per channel.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/image.h"

namespace bounce {

void tonemap_srgb8(const Image& linear, float exposure_ev, std::vector<uint8_t>& out);

}  // namespace bounce
