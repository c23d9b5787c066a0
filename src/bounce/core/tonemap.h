// Tone mapping to 8-bit sRGB: exposure, clamp, then the sRGB curve. The renderer's tone-map
// stage and PNG output both use it.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/image.h"

namespace bounce {

// Writes 3 bytes per pixel, row-major from the top row.
void tonemap_srgb8(const Image& linear, float exposure_ev, std::vector<uint8_t>& out);

}  // namespace bounce
