// Radiance RGBE (.hdr) images: our own reader, because stb's does not notice a truncated file.
// load_image (image_io.h) calls it for .hdr; every failure throws Error naming the file.
#pragma once

#include <cstddef>
#include <string>

#include "bounce/core/image.h"

namespace bounce {

// Decodes a whole .hdr file (`path` names it in messages): the "#?" signature, header lines up
// to a blank line (FORMAT must be 32-bit_rle_rgbe when given; EXPOSURE is ignored, as most
// readers do), the standard resolution line "-Y height +X width", then the scanlines, flat or
// with the adaptive run-length encoding of Ward's Radiance.
Image decode_rgbe(const std::string& path, const unsigned char* data, size_t size);

}  // namespace bounce
