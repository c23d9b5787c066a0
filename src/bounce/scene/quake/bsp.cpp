#include "bounce/scene/quake/bsp.h"

#include <bit>
#include <cmath>
#include <cstring>

#include "bounce/core/error.h"

namespace bounce::quake {

namespace {

constexpr int32_t kVersion = 46;

constexpr std::array<const char*, kLumpCount> kLumpNames = {
    "entities",     "textures", "planes",    "nodes",         "leafs",     "leaf faces",
    "leaf brushes", "models",   "brushes",   "brush sides",   "vertices",  "mesh vertices",
    "effects",      "faces",    "lightmaps", "light volumes", "visibility"};

// Little-endian reads from a checked span (the format is little-endian; so is every machine we
// build for, which memcpy relies on).
static_assert(std::endian::native == std::endian::little, "the IBSP reader assumes little-endian");

int32_t read_i32(const uint8_t* p) {
  int32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
float read_f32(const uint8_t* p) {
  float v;
  std::memcpy(&v, p, 4);
  return v;
}
std::array<float, 3> read_vec3(const uint8_t* p) {
  return {read_f32(p), read_f32(p + 4), read_f32(p + 8)};
}

struct LumpBytes {
  const uint8_t* data = nullptr;
  size_t size = 0;
};

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  void header() {
    if (bytes_.size() < kHeaderBytes)
      fail("{}: not a Quake 3 map: {} bytes is shorter than the {}-byte IBSP header", name_,
           bytes_.size(), kHeaderBytes);
    if (std::memcmp(bytes_.data(), "IBSP", 4) != 0)
      fail("{}: not a Quake 3 map: the file does not start with \"IBSP\"", name_);
    const int32_t version = read_i32(bytes_.data() + 4);
    if (version != kVersion)
      fail("{}: IBSP version {} is not supported (only {}, Quake 3 Arena)", name_, version,
           kVersion);
    for (int l = 0; l < kLumpCount; ++l) {
      const int64_t offset = read_i32(bytes_.data() + 8 + 8 * l);
      const int64_t length = read_i32(bytes_.data() + 12 + 8 * l);
      if (offset < 0 || length < 0)
        fail("{}: lump '{}' has a negative offset or length ({}, {})", name_, lump_name(l), offset,
             length);
      if (length > 0 &&
          (offset < int64_t(kHeaderBytes) || offset + length > int64_t(bytes_.size())))
        fail(
            "{}: lump '{}' (bytes {} to {}) lies outside the file ({} bytes); the file is "
            "truncated or corrupt",
            name_, lump_name(l), offset, offset + length, bytes_.size());
      if (length > 0) lumps_[size_t(l)] = {bytes_.data() + offset, size_t(length)};
    }
  }

  // The lump's records: its size must be a whole number of them.
  LumpBytes records(int lump, size_t record_bytes, size_t* count) const {
    const LumpBytes l = lumps_[size_t(lump)];
    if (l.size % record_bytes != 0)
      fail("{}: lump '{}' is {} bytes, not a whole number of {}-byte records", name_,
           lump_name(lump), l.size, record_bytes);
    *count = l.size / record_bytes;
    return l;
  }

  LumpBytes lump(int l) const { return lumps_[size_t(l)]; }
  const std::string& name() const { return name_; }

 private:
  std::span<const uint8_t> bytes_;
  const std::string& name_;
  std::array<LumpBytes, kLumpCount> lumps_{};
};

bool finite(const std::array<float, 3>& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void read_textures(const Reader& r, BspFile& out) {
  size_t count = 0;
  const LumpBytes l = r.records(kLumpTextures, kTextureBytes, &count);
  out.textures.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* p = l.data + i * kTextureBytes;
    const char* name = reinterpret_cast<const char*>(p);
    out.textures[i].name.assign(name, strnlen(name, 64));
    out.textures[i].surface_flags = uint32_t(read_i32(p + 64));
    out.textures[i].content_flags = uint32_t(read_i32(p + 68));
  }
}

void read_vertices(const Reader& r, BspFile& out) {
  size_t count = 0;
  const LumpBytes l = r.records(kLumpVertices, kVertexBytes, &count);
  out.vertices.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* p = l.data + i * kVertexBytes;
    BspVertex& v = out.vertices[i];
    v.position = read_vec3(p);
    v.uv = {read_f32(p + 12), read_f32(p + 16)};
    v.normal = read_vec3(p + 28);
    if (!finite(v.position) || !finite(v.normal) || !std::isfinite(v.uv[0]) ||
        !std::isfinite(v.uv[1]))
      fail(
          "{}: lump 'vertices': vertex {} has a non-finite position, normal or texture "
          "coordinate",
          r.name(), i);
  }
}

void read_mesh_vertices(const Reader& r, BspFile& out) {
  size_t count = 0;
  const LumpBytes l = r.records(kLumpMeshVertices, kMeshVertexBytes, &count);
  out.mesh_vertices.resize(count);
  for (size_t i = 0; i < count; ++i) out.mesh_vertices[i] = read_i32(l.data + 4 * i);
}

// A range [first, first + count) must lie inside [0, size).
bool range_inside(int64_t first, int64_t count, size_t size) {
  return first >= 0 && count >= 0 && first + count <= int64_t(size);
}

void check_face(const Reader& r, const BspFile& b, size_t i, const BspFace& f) {
  const std::string& n = r.name();
  if (f.texture < 0 || size_t(f.texture) >= b.textures.size())
    fail("{}: lump 'faces': face {} uses texture {}, out of range ({} textures)", n, i, f.texture,
         b.textures.size());
  switch (FaceType(f.type)) {
    case FaceType::kPolygon:
    case FaceType::kMesh: {
      if (!range_inside(f.first_vertex, f.vertex_count, b.vertices.size()))
        fail("{}: lump 'faces': face {} uses vertices {} to {}, out of range ({} vertices)", n, i,
             int64_t(f.first_vertex), int64_t(f.first_vertex) + f.vertex_count, b.vertices.size());
      if (!range_inside(f.first_mesh_vertex, f.mesh_vertex_count, b.mesh_vertices.size()))
        fail(
            "{}: lump 'faces': face {} uses mesh vertices {} to {}, out of range ({} mesh "
            "vertices)",
            n, i, int64_t(f.first_mesh_vertex), int64_t(f.first_mesh_vertex) + f.mesh_vertex_count,
            b.mesh_vertices.size());
      if (f.mesh_vertex_count % 3 != 0)
        fail("{}: lump 'faces': face {} has {} mesh vertices, not a whole number of triangles", n,
             i, f.mesh_vertex_count);
      for (int32_t k = 0; k < f.mesh_vertex_count; ++k) {
        const int32_t m = b.mesh_vertices[size_t(f.first_mesh_vertex + k)];
        if (m < 0 || m >= f.vertex_count)
          fail(
              "{}: lump 'mesh vertices': entry {} (of face {}) is {}, outside the face's {} "
              "vertices",
              n, f.first_mesh_vertex + k, i, m, f.vertex_count);
      }
      break;
    }
    case FaceType::kPatch: {
      const int32_t w = f.patch_size[0], h = f.patch_size[1];
      if (w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || w > 4097 || h > 4097)
        fail(
            "{}: lump 'faces': patch face {} has a {} x {} control grid (each side must be odd "
            "and at least 3)",
            n, i, w, h);
      if (int64_t(w) * h != f.vertex_count)
        fail("{}: lump 'faces': patch face {} has {} vertices for a {} x {} control grid", n, i,
             f.vertex_count, w, h);
      if (!range_inside(f.first_vertex, f.vertex_count, b.vertices.size()))
        fail("{}: lump 'faces': face {} uses vertices {} to {}, out of range ({} vertices)", n, i,
             int64_t(f.first_vertex), int64_t(f.first_vertex) + f.vertex_count, b.vertices.size());
      break;
    }
    case FaceType::kBillboard:
      break;  // skipped by the loader: nothing it refers to is read
    default:
      fail("{}: lump 'faces': face {} has unknown type {} (1 to 4 are defined)", n, i, f.type);
  }
}

void read_faces(const Reader& r, BspFile& out) {
  size_t count = 0;
  const LumpBytes l = r.records(kLumpFaces, kFaceBytes, &count);
  out.faces.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* p = l.data + i * kFaceBytes;
    BspFace& f = out.faces[i];
    f.texture = read_i32(p);
    f.type = read_i32(p + 8);
    f.first_vertex = read_i32(p + 12);
    f.vertex_count = read_i32(p + 16);
    f.first_mesh_vertex = read_i32(p + 20);
    f.mesh_vertex_count = read_i32(p + 24);
    f.normal = read_vec3(p + 84);
    f.patch_size = {read_i32(p + 96), read_i32(p + 100)};
    check_face(r, out, i, f);
  }
}

void read_models(const Reader& r, BspFile& out) {
  size_t count = 0;
  const LumpBytes l = r.records(kLumpModels, kModelBytes, &count);
  out.models.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* p = l.data + i * kModelBytes;
    BspModel& m = out.models[i];
    m.mins = read_vec3(p);
    m.maxs = read_vec3(p + 12);
    m.first_face = read_i32(p + 24);
    m.face_count = read_i32(p + 28);
    if (!range_inside(m.first_face, m.face_count, out.faces.size()))
      fail("{}: lump 'models': model {} uses faces {} to {}, out of range ({} faces)", r.name(), i,
           int64_t(m.first_face), int64_t(m.first_face) + m.face_count, out.faces.size());
  }
}

}  // namespace

const char* lump_name(int lump) {
  return lump >= 0 && lump < kLumpCount ? kLumpNames[size_t(lump)] : "unknown";
}

BspFile parse_bsp(std::span<const uint8_t> bytes, const std::string& name) {
  Reader r(bytes, name);
  r.header();
  BspFile out;
  const LumpBytes e = r.lump(kLumpEntities);
  const char* text = reinterpret_cast<const char*>(e.data);
  out.entities.assign(text, e.size ? strnlen(text, e.size) : 0);
  read_textures(r, out);
  read_vertices(r, out);
  read_mesh_vertices(r, out);
  read_faces(r, out);
  read_models(r, out);
  return out;
}

}  // namespace bounce::quake
