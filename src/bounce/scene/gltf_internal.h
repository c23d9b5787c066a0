// What the files of the glTF loader share: the conversion context and the checked reads from the
// model. load_gltf.cpp reads the file and runs the steps; gltf_buffers.cpp, gltf_materials.cpp,
// gltf_nodes.cpp and gltf_animation.cpp each hold one. Private to the scene layer (not installed).
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "bounce/core/math.h"
#include "bounce/scene/scene.h"

namespace bounce::gltf {

namespace tg = tinygltf;

// The extensions whose meaning we implement; a file that requires any other is refused.
extern const std::set<std::string> kSupportedExtensions;

// gltf_preflight.cpp: reads the file's JSON before tinygltf and refuses a glTF 1.0 file or a
// required extension we lack by name (throws Error); warns about values of the wrong type.
void preflight(const std::string& path);

// Everything the conversion shares: the model, the scene being built and what was converted.
struct Context {
  Context(const std::string& p, const tg::Model& m, Scene& s) : path(p), model(m), scene(s) {}

  const std::string& path;
  const tg::Model& model;
  Scene& scene;
  std::vector<int> material_of;  // glTF material -> scene material (-1: not yet converted)
  int default_material = -1;     // for primitives without a material
  // (glTF image, how it is read: gltf_materials.cpp's TextureKind) -> scene texture (-1: none)
  std::map<std::pair<int, int>, int> texture_of;
  std::set<std::string> ignored;  // unsupported features met, reported once
  std::set<int> skipped_modes;    // primitive modes other than triangles, reported once
  bool camera_found = false;
  // What the node walk produced, per glTF node (for animations): whether the node was reached,
  // its parent (-1 for a root), its world transform and the scene meshes and lights it made
  // ([first, end) ranges; a node's primitives and its light are consecutive).
  std::vector<char> visited;
  std::vector<int> parent_of;
  std::vector<mat4> world_of;
  std::vector<std::pair<uint32_t, uint32_t>> meshes_of, lights_of;
  std::vector<int> walk_order;  // visited nodes, parents first
};

// gltf_buffers.cpp: checked reads. Every index, count and byte range is checked before use and a
// bad one is an Error naming the file and `what`.

struct Bytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
};

// The bytes of a bufferView after checking that it lies inside its buffer.
Bytes buffer_view_bytes(const Context& ctx, int index, const std::string& what);

// A checked accessor: `count` elements of `components` values, `stride` bytes apart.
struct AccessorData {
  const unsigned char* data = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

AccessorData accessor_data(const Context& ctx, int index, const std::string& what);
void expect_type(const Context& ctx, int index, const AccessorData& a, int components,
                 const char* type, const std::string& what);

template <typename T>
T read_at(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));  // accessors need not be aligned
  return value;
}

std::vector<vec3> read_vec3(const Context& ctx, int index, const std::string& what);
std::vector<vec2> read_uv(const Context& ctx, int index, const std::string& what);
std::vector<uint32_t> read_indices(const Context& ctx, int index, const std::string& what);

// A number member of a JSON object, or `fallback` when it is missing or not a number.
double number_or(const tg::Value& object, const char* key, double fallback);
// The object of a named extension, or null.
const tg::Value* extension(const tg::ExtensionMap& extensions, const char* name);
vec3 vec3_from(const Context& ctx, const std::vector<double>& v, size_t min_size,
               const std::string& what);
float finite_number(const Context& ctx, double value, const std::string& what);

// gltf_materials.cpp: the scene material for a glTF material index (-1: the default material),
// converted on first use.
uint32_t scene_material(Context& ctx, int index, const std::string& what);

// gltf_nodes.cpp: walks the default scene's node tree into meshes, lights and the camera, filling
// the per-node fields of the context.
void walk_nodes(Context& ctx);
mat4 local_transform(const Context& ctx, const tg::Node& node, int index);

// gltf_animation.cpp: the node animations as tracks (after walk_nodes).
void read_animations(Context& ctx);

}  // namespace bounce::gltf
