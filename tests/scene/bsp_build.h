// Writes small Quake 3 IBSP files and stored (uncompressed) zip archives for the Quake loader
// tests: valid ones, and the raw bytes to break on purpose.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace bounce::scene_test {

struct BspBuild {
  struct Vertex {
    std::array<float, 3> p{}, n{0, 0, 1};
    std::array<float, 2> uv{};
  };
  struct Face {
    int32_t texture = 0, type = 1, first_vertex = 0, vertex_count = 0;
    int32_t first_mesh_vertex = 0, mesh_vertex_count = 0;
    std::array<float, 3> normal{0, 0, 1};
    std::array<int32_t, 2> size{};
  };
  std::string entities = "{\n\"classname\" \"worldspawn\"\n}\n";
  std::vector<std::pair<std::string, std::array<int32_t, 2>>> textures;  // name, flags, contents
  std::vector<Vertex> vertices;
  std::vector<int32_t> mesh_vertices;
  std::vector<Face> faces;

  // A floor quad (two triangles, z = 0, facing +z) 128 units wide, with one texture.
  static BspBuild floor() {
    BspBuild b;
    b.textures.push_back({"textures/test/floor", {0, 1}});
    const float s = 128.0f;
    for (auto xy : {std::array<float, 2>{0, 0}, {s, 0}, {s, s}, {0, s}})
      b.vertices.push_back({{xy[0], xy[1], 0.0f}, {0, 0, 1}, {xy[0] / s, xy[1] / s}});
    // Quake winds front faces clockwise seen from the front (+z here).
    b.mesh_vertices = {0, 2, 1, 0, 3, 2};
    Face f;
    f.vertex_count = 4;
    f.mesh_vertex_count = 6;
    b.faces.push_back(f);
    return b;
  }

  std::string bytes() const {
    std::array<std::string, 17> lumps;
    lumps[0] = entities + std::string(1, '\0');
    for (const auto& [name, fc] : textures) {
      std::string rec(72, '\0');
      std::memcpy(rec.data(), name.data(), std::min<size_t>(name.size(), 64));
      std::memcpy(rec.data() + 64, fc.data(), 8);
      lumps[1] += rec;
    }
    for (const auto& v : vertices) {
      std::string rec(44, '\0');
      std::memcpy(rec.data(), v.p.data(), 12);
      std::memcpy(rec.data() + 12, v.uv.data(), 8);
      std::memcpy(rec.data() + 28, v.n.data(), 12);
      lumps[10] += rec;
    }
    lumps[11].assign(reinterpret_cast<const char*>(mesh_vertices.data()), mesh_vertices.size() * 4);
    for (const auto& f : faces) {
      std::string rec(104, '\0');
      const int32_t head[7] = {
          f.texture,          0, f.type, f.first_vertex, f.vertex_count, f.first_mesh_vertex,
          f.mesh_vertex_count};
      std::memcpy(rec.data(), head, sizeof(head));
      std::memcpy(rec.data() + 84, f.normal.data(), 12);
      std::memcpy(rec.data() + 96, f.size.data(), 8);
      lumps[13] += rec;
    }
    std::string out = "IBSP";
    const int32_t version = 46;
    out.append(reinterpret_cast<const char*>(&version), 4);
    int32_t offset = 8 + 8 * 17;
    for (const auto& l : lumps) {
      const int32_t entry[2] = {offset, int32_t(l.size())};
      out.append(reinterpret_cast<const char*>(entry), 8);
      offset += int32_t(l.size());
    }
    for (const auto& l : lumps) out += l;
    return out;
  }
};

// Offset of lump l's directory entry (offset, then length) in a .bsp.
constexpr size_t lump_entry(int l) {
  return 8 + 8 * size_t(l);
}

inline void put_i32(std::string& bytes, size_t at, int32_t v) {
  std::memcpy(&bytes[at], &v, 4);
}
inline int32_t get_i32(const std::string& bytes, size_t at) {
  int32_t v;
  std::memcpy(&v, &bytes[at], 4);
  return v;
}

inline uint32_t crc32(const std::string& data) {
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char c : data) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// A zip archive with the given entries stored uncompressed (PKWARE APPNOTE layout).
inline std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& entries) {
  auto u16 = [](std::string& s, uint16_t v) { s.append(reinterpret_cast<const char*>(&v), 2); };
  auto u32 = [](std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  std::string out, central;
  for (const auto& [name, data] : entries) {
    const uint32_t offset = uint32_t(out.size()), crc = crc32(data), size = uint32_t(data.size());
    u32(out, 0x04034b50);
    for (uint16_t v : {uint16_t(20), uint16_t(0), uint16_t(0), uint16_t(0), uint16_t(0x21)})
      u16(out, v);
    u32(out, crc), u32(out, size), u32(out, size);
    u16(out, uint16_t(name.size())), u16(out, 0);
    out += name + data;
    u32(central, 0x02014b50);
    for (uint16_t v :
         {uint16_t(20), uint16_t(20), uint16_t(0), uint16_t(0), uint16_t(0), uint16_t(0x21)})
      u16(central, v);
    u32(central, crc), u32(central, size), u32(central, size);
    for (uint16_t v : {uint16_t(name.size()), uint16_t(0), uint16_t(0), uint16_t(0), uint16_t(0)})
      u16(central, v);
    u32(central, 0), u32(central, offset);
    central += name;
  }
  const uint32_t central_offset = uint32_t(out.size());
  out += central;
  u32(out, 0x06054b50);
  for (uint16_t v : {uint16_t(0), uint16_t(0), uint16_t(entries.size()), uint16_t(entries.size())})
    u16(out, v);
  u32(out, uint32_t(central.size())), u32(out, central_offset);
  u16(out, 0);
  return out;
}

}  // namespace bounce::scene_test
