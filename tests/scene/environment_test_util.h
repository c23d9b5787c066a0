// Environment maps for tests: small synthetic maps and a Radiance .hdr writer (flat RGBE
// pixels, the uncompressed form the format allows), so files can be made byte by byte.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "bounce/core/image.h"
#include "bounce/core/rng.h"
#include "bounce/scene/mesh.h"
#include "scene/hand_built_scenes.h"

namespace bounce::scene_test {

// Radiance RGBE: a shared exponent and three 8-bit mantissas. Powers of two and their small
// multiples (1, 0.5, 3, ...) survive exactly.
inline std::string rgbe_pixel(vec3 c) {
  const float v = std::max(c.x, std::max(c.y, c.z));
  if (v < 1e-32f) return std::string(4, '\0');
  int e = 0;
  const float scale = std::frexp(v, &e) * 256.0f / v;
  std::string p(4, '\0');
  p[0] = char(uint8_t(c.x * scale));
  p[1] = char(uint8_t(c.y * scale));
  p[2] = char(uint8_t(c.z * scale));
  p[3] = char(uint8_t(e + 128));
  return p;
}

// The four channels of one scanline in Radiance's adaptive run-length encoding: runs of three
// or more equal bytes as (128 + count, byte), the rest as (count, bytes...).
inline std::string rle_scanline(const std::string& pixels, int width) {
  std::string out = {char(2), char(2), char(width >> 8), char(width & 0xff)};
  for (int c = 0; c < 4; ++c) {
    const auto at = [&](int x) { return pixels[size_t(x) * 4 + size_t(c)]; };
    int x = 0;
    while (x < width) {
      int run = 1;
      while (x + run < width && run < 127 && at(x + run) == at(x)) ++run;
      if (run >= 3) {
        out += char(128 + run);
        out += at(x);
        x += run;
        continue;
      }
      int count = 0;
      std::string literal;
      while (x < width && count < 128) {
        if (x + 2 < width && at(x) == at(x + 1) && at(x) == at(x + 2)) break;
        literal += at(x++);
        ++count;
      }
      out += char(count);
      out += literal;
    }
  }
  return out;
}

// A whole .hdr file of `image`, top row first: flat pixels below 8 texels wide, run-length
// encoded scanlines from 8 on (as Radiance writes them).
inline std::string hdr_file(const Image& image) {
  std::string out = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n-Y " +
                    std::to_string(image.height()) + " +X " + std::to_string(image.width()) + "\n";
  for (int y = 0; y < image.height(); ++y) {
    std::string row;
    for (int x = 0; x < image.width(); ++x) row += rgbe_pixel(image.at(x, y));
    out += image.width() >= 8 ? rle_scanline(row, image.width()) : row;
  }
  return out;
}

// A map of w x h texels with luminances spread over two orders of magnitude, one bright
// "sun" texel and one black row, so sampling by luminance matters and zero weights occur.
inline Image synthetic_map(int w, int h, uint32_t seed = 7) {
  Image image(w, h);
  Pcg32 rng(seed, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float a = rng.next_float(), b = rng.next_float(), c = rng.next_float();
      image.at(x, y) = vec3(0.05f + 2.0f * a * a, 0.05f + 1.5f * b, 0.1f + c);
    }
  for (int x = 0; x < w; ++x) image.at(x, h - 1) = vec3(0.0f);  // black ground row
  image.at(w / 3, h / 4) = vec3(40.0f, 36.0f, 30.0f);           // the sun
  return image;
}

// A faceted sphere (latitude-longitude, flat faces: no vertex normals), facing outwards.
inline Mesh faceted_sphere(const std::string& name, vec3 centre, float radius, int rings,
                           int segments, uint32_t material) {
  Mesh mesh;
  mesh.name = name;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i <= segments; ++i) {
      const float theta = kPi * float(j) / float(rings), phi = kTwoPi * float(i) / float(segments);
      mesh.positions.push_back(centre + radius * vec3(std::sin(theta) * std::cos(phi),
                                                      std::cos(theta),
                                                      std::sin(theta) * std::sin(phi)));
    }
  const auto at = [&](int j, int i) { return uint32_t(j * (segments + 1) + i); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      // Winding chosen so cross(b - a, c - a) points away from the centre.
      if (j > 0) mesh.triangles.push_back({at(j, i), at(j, i + 1), at(j + 1, i)});
      if (j < rings - 1) mesh.triangles.push_back({at(j, i + 1), at(j + 1, i + 1), at(j + 1, i)});
    }
  mesh.materials.assign(mesh.triangles.size(), material);
  return mesh;
}

// A box of side `size` standing on y = base with no lid: five faces, a cavity open to the sky.
inline Mesh open_box(const std::string& name, vec3 centre, float size, uint32_t material) {
  Mesh mesh;
  mesh.name = name;
  const float h = 0.5f * size;
  const vec3 lo = centre - vec3(h, 0.0f, h);
  add_quad(mesh, lo, vec3(0, 0, size), vec3(size, 0, 0), material);  // floor, up
  add_quad(mesh, lo, vec3(0, size, 0), vec3(0, 0, size), material);  // x = lo
  add_quad(mesh, lo + vec3(size, 0, 0), vec3(0, 0, size), vec3(0, size, 0), material);
  add_quad(mesh, lo, vec3(size, 0, 0), vec3(0, size, 0), material);  // z = lo
  add_quad(mesh, lo + vec3(0, 0, size), vec3(0, size, 0), vec3(size, 0, 0), material);
  return mesh;
}

}  // namespace bounce::scene_test
