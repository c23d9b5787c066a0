// Quake 3 IBSP version 46 files, parsed into plain records. The layout follows Kekoa Proudfoot's
// "Unofficial Quake 3 Map Specs" (2000); the flag values are those of id Software's GPL Quake 3
// source (surfaceflags.h). Only the lumps a renderer needs are read: lightmaps, light volumes,
// visibility and the BSP tree itself are ignored (we compute light; Embree builds its own tree).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace bounce::quake {

enum Lump : int {
  kLumpEntities = 0,
  kLumpTextures = 1,
  kLumpPlanes = 2,
  kLumpNodes = 3,
  kLumpLeafs = 4,
  kLumpLeafFaces = 5,
  kLumpLeafBrushes = 6,
  kLumpModels = 7,
  kLumpBrushes = 8,
  kLumpBrushSides = 9,
  kLumpVertices = 10,
  kLumpMeshVertices = 11,
  kLumpEffects = 12,
  kLumpFaces = 13,
  kLumpLightmaps = 14,
  kLumpLightVolumes = 15,
  kLumpVisibility = 16,
  kLumpCount = 17,
};

// The lump's name as the specification calls it, for messages.
const char* lump_name(int lump);

// Record sizes in bytes (the specification's).
constexpr size_t kHeaderBytes = 8 + 8 * kLumpCount;
constexpr size_t kTextureBytes = 72;  // name[64], flags, contents
constexpr size_t kVertexBytes = 44;   // position[3], uv[2], lightmap uv[2], normal[3], rgba[4]
constexpr size_t kMeshVertexBytes = 4;
constexpr size_t kFaceBytes = 104;
constexpr size_t kModelBytes = 40;

// Surface flags (texture "flags") and content flags this loader looks at.
constexpr uint32_t kSurfSky = 0x4;
constexpr uint32_t kSurfNoDraw = 0x80;
constexpr uint32_t kSurfHint = 0x100;
constexpr uint32_t kSurfSkip = 0x200;
constexpr uint32_t kSurfNonSolid = 0x4000;
constexpr uint32_t kContentsFog = 0x40;

enum class FaceType : int32_t { kPolygon = 1, kPatch = 2, kMesh = 3, kBillboard = 4 };

struct BspTexture {
  std::string name;  // e.g. "textures/base_wall/metal", without extension
  uint32_t surface_flags = 0;
  uint32_t content_flags = 0;
};

struct BspVertex {
  std::array<float, 3> position{};  // Quake units, Z up
  std::array<float, 2> uv{};        // surface texture coordinates (t = 0 at the image's top)
  std::array<float, 3> normal{};
};

struct BspFace {
  int32_t texture = 0;
  int32_t type = 0;  // FaceType
  int32_t first_vertex = 0, vertex_count = 0;
  int32_t first_mesh_vertex = 0, mesh_vertex_count = 0;
  std::array<float, 3> normal{};
  std::array<int32_t, 2> patch_size{};  // control points across and down, for patches
};

struct BspModel {
  std::array<float, 3> mins{}, maxs{};
  int32_t first_face = 0, face_count = 0;
};

struct BspFile {
  std::string entities;  // the entity text (without its trailing NUL)
  std::vector<BspTexture> textures;
  std::vector<BspVertex> vertices;
  std::vector<int32_t> mesh_vertices;  // offsets relative to a face's first vertex
  std::vector<BspFace> faces;
  std::vector<BspModel> models;
};

// Parses and checks a whole .bsp held in memory. Every count, offset and index is checked
// against the buffer and the lumps it refers to; a problem throws Error naming `name`, the lump
// and the record. Non-finite vertex data is an error too.
BspFile parse_bsp(std::span<const uint8_t> bytes, const std::string& name);

}  // namespace bounce::quake
