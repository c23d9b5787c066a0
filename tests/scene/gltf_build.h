// Test helpers for building glTF fixtures in memory with tinygltf: raw data appended as
// bufferViews and accessors, and JSON-like extension values.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

namespace bounce::gltf_build {

// Appends values to buffer 0 as a new bufferView and accessor; returns the accessor.
template <typename T>
int add_data(tinygltf::Model& m, const std::vector<T>& values, int component_type, int type,
             size_t count) {
  std::vector<unsigned char>& data = m.buffers[0].data;
  while (data.size() % 4) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = values.size() * sizeof(T);
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  data.insert(data.end(), bytes, bytes + view.byteLength);
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = int(m.bufferViews.size() - 1);
  a.componentType = component_type;
  a.type = type;
  a.count = count;
  m.accessors.push_back(a);
  return int(m.accessors.size() - 1);
}

// Writes an 8-bit RGBA image (row-major from the top row) as an uncompressed TGA, which the glTF
// loader's image decoder reads like a PNG: a texture with an alpha channel, written by hand.
inline void write_tga_rgba(const std::string& path, int width, int height,
                           const std::vector<unsigned char>& rgba) {
  std::vector<unsigned char> out(18, 0);
  out[2] = 2;  // uncompressed true colour
  out[12] = uint8_t(width & 255);
  out[13] = uint8_t(width >> 8);
  out[14] = uint8_t(height & 255);
  out[15] = uint8_t(height >> 8);
  out[16] = 32;        // bits per pixel
  out[17] = 0x20 | 8;  // top-left origin, 8 alpha bits
  for (size_t p = 0; p + 3 < rgba.size(); p += 4)
    out.insert(out.end(), {rgba[p + 2], rgba[p + 1], rgba[p], rgba[p + 3]});  // BGRA
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
}

inline tinygltf::Value object(
    std::initializer_list<std::pair<const std::string, tinygltf::Value>> members) {
  return tinygltf::Value(tinygltf::Value::Object(members));
}

}  // namespace bounce::gltf_build
