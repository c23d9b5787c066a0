#include "bounce/core/rgbe.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string_view>
#include <vector>

#include "bounce/core/error.h"

namespace bounce {

namespace {

// A text line of the header (without its newline); false at the end of the data.
bool next_line(const unsigned char* data, size_t size, size_t& at, std::string_view& line) {
  if (at >= size) return false;
  size_t end = at;
  while (end < size && data[end] != '\n') ++end;
  line = std::string_view(reinterpret_cast<const char*>(data) + at, end - at);
  at = end < size ? end + 1 : end;
  return true;
}

// One pixel: a shared exponent over three mantissas, decoded as Radiance's colr_color does
// ((m + 0.5) * 2^(e - 136)); exponent 0 is black.
vec3 rgbe_to_rgb(const uint8_t* p) {
  if (p[3] == 0) return vec3(0.0f);
  const float f = std::ldexp(1.0f, int(p[3]) - 136);
  return {(float(p[0]) + 0.5f) * f, (float(p[1]) + 0.5f) * f, (float(p[2]) + 0.5f) * f};
}

}  // namespace

Image decode_rgbe(const std::string& path, const unsigned char* data, size_t size) {
  size_t at = 0;
  std::string_view line;
  if (size < 2 || data[0] != '#' || data[1] != '?')
    fail("cannot read {}: not a Radiance .hdr file (no '#?RADIANCE' or '#?RGBE' signature)", path);
  next_line(data, size, at, line);
  bool blank = false;
  while (next_line(data, size, at, line)) {
    if (line.empty()) {
      blank = true;
      break;
    }
    if (line.starts_with("FORMAT=") && line != "FORMAT=32-bit_rle_rgbe")
      fail("cannot read {}: unsupported pixel format '{}' (only 32-bit_rle_rgbe)", path,
           line.substr(7));
  }
  if (!blank) fail("cannot read {}: the header has no end (no blank line before the size)", path);
  if (!next_line(data, size, at, line)) fail("cannot read {}: no resolution line", path);
  int height = 0, width = 0, consumed = 0;
  const std::string resolution(line);
  if (std::sscanf(resolution.c_str(), "-Y %d +X %d%n", &height, &width, &consumed) != 2 ||
      size_t(consumed) != resolution.size())
    fail("cannot read {}: unsupported resolution line '{}' (expected '-Y height +X width')", path,
         resolution);
  // Checked before allocating: a corrupt size must not ask for gigabytes, and every scanline
  // takes at least a byte.
  if (width <= 0 || height <= 0 || int64_t(width) * height > (int64_t(1) << 28) ||
      size_t(height) > size - at)
    fail("cannot read {}: invalid image size {}x{} for a file of {} bytes", path, width, height,
         size);

  Image image(width, height);
  std::vector<uint8_t> row(size_t(width) * 4);
  const auto truncated = [&](int y) {
    fail("cannot read {}: the file is truncated in scanline {} of {}", path, y, height);
  };
  for (int y = 0; y < height; ++y) {
    const bool rle = width >= 8 && width < 0x8000 && at + 4 <= size && data[at] == 2 &&
                     data[at + 1] == 2 && ((int(data[at + 2]) << 8) | data[at + 3]) == width;
    if (!rle) {
      if (at + 4 <= size && data[at] == 1 && data[at + 1] == 1 && data[at + 2] == 1)
        fail("cannot read {}: scanline {} uses the old run-length encoding, not supported", path,
             y);
      if (size - at < row.size()) truncated(y);
      std::copy(data + at, data + at + row.size(), row.begin());
      at += row.size();
    } else {
      at += 4;
      // Each channel in turn: a count above 128 repeats the next byte (count - 128) times,
      // otherwise that many bytes follow.
      for (int c = 0; c < 4; ++c) {
        int x = 0;
        while (x < width) {
          if (at >= size) truncated(y);
          int count = data[at++];
          const bool run = count > 128;
          if (run) count -= 128;
          if (count == 0 || x + count > width)
            fail("cannot read {}: scanline {} has a run of {} past its {} pixels", path, y, count,
                 width);
          if (run) {
            if (at >= size) truncated(y);
            for (int k = 0; k < count; ++k) row[size_t(x + k) * 4 + c] = data[at];
            ++at;
          } else {
            if (size - at < size_t(count)) truncated(y);
            for (int k = 0; k < count; ++k) row[size_t(x + k) * 4 + c] = data[at++];
          }
          x += count;
        }
      }
    }
    for (int x = 0; x < width; ++x) image.at(x, y) = rgbe_to_rgb(&row[size_t(x) * 4]);
  }
  return image;
}

}  // namespace bounce
