// Reading and writing images: PNG/JPEG/TGA/BMP (8-bit sRGB), OpenEXR and PFM (linear float).
// Every failure throws Error with the path and the problem; every save is atomic (a temporary file
// in the same directory renamed over the target), so a failed save leaves no partial file behind.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "bounce/core/image.h"

namespace bounce {

// Loads an image as linear RGB, choosing the format by the (case-insensitive) extension:
// .png/.jpg/.jpeg/.tga/.bmp are decoded from sRGB (alpha is dropped), .exr reads the R, G and B
// channels, .hdr reads Radiance RGBE, .pfm reads colour ("PF") and greyscale ("Pf") files.
Image load_image(const std::string& path);

// Saves an image by extension: .png is scaled by 2^exposure_ev, clamped and sRGB-encoded to 8 bits;
// .exr (32-bit float R, G, B, ZIP) and .pfm are linear and unclamped, ignoring the exposure.
void save_image(const std::string& path, const Image& image, float exposure_ev = 0.0f);

// Saves an already tone-mapped 8-bit RGB buffer (width * height * 3 bytes, row-major, top row
// first) as a PNG.
void save_png_rgb8(const std::string& path, int width, int height, const uint8_t* rgb);

// Writes text (a JSON report, ...) to `path` with the same atomic rename as the image savers.
// Like them it abandons the write when SIGINT or SIGTERM arrived, unless
// finish_when_interrupted (a checkpoint: the very file an interrupt should leave).
void save_text_file(const std::string& path, const std::string& text,
                    bool finish_when_interrupted = false);

// Named text values stored in an EXR file's header beside the pixels (what made the image: a
// reference slice's scene, seed and samples, read back by bounce merge).
using ImageAttributes = std::map<std::string, std::string>;

// Saves linear pixels as .exr (like save_image) with `attributes` as string attributes of the
// header; throws Error for another extension.
void save_exr(const std::string& path, const Image& image, const ImageAttributes& attributes);

// Loads an .exr (like load_image) and every string attribute of its header.
Image load_exr(const std::string& path, ImageAttributes& attributes);

}  // namespace bounce
