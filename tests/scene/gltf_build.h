// Test helpers for building glTF fixtures in memory with tinygltf: raw data appended as
// bufferViews and accessors, and JSON-like extension values.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <stb_image_write.h>
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

// Writes an 8-bit RGBA image (row-major from the top row) as a PNG: a texture with an alpha
// channel. PNG, because tinygltf's writer keeps a relative uri only for PNG and JPEG images.
inline void write_png_rgba(const std::string& path, int width, int height,
                           const std::vector<unsigned char>& rgba) {
  if (!stbi_write_png(path.c_str(), width, height, 4, rgba.data(), width * 4))
    throw std::runtime_error("cannot write " + path);
}

inline tinygltf::Value object(
    std::initializer_list<std::pair<const std::string, tinygltf::Value>> members) {
  return tinygltf::Value(tinygltf::Value::Object(members));
}

}  // namespace bounce::gltf_build
