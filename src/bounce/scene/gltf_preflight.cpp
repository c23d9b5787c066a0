// A look at a glTF file's JSON before tinygltf converts it. tinygltf reports a glTF 1.0 file, or
// one whose meshes need an extension (Draco), only by what then goes wrong ("no triangles",
// "invalid bufferView"), and it drops a value of the wrong type (a string where an index belongs)
// without a word. Reading the JSON first lets each of these be named as what it is.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include <nlohmann/json.hpp>

#include "bounce/core/error.h"
#include "bounce/scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

using json = nlohmann::json;

// The JSON text of a .gltf file, or of a .glb's first chunk (GLB 2.0: a 12-byte header, then
// chunks of length, type and data; the first chunk is JSON). Empty when it cannot be found:
// tinygltf then reports the container's problem itself.
std::string json_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char header[20] = {};
  if (!in.read(header, 4)) return {};
  if (std::memcmp(header, "glTF", 4) != 0) {
    in.seekg(0);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (!in.read(header + 4, 16)) return {};
  uint32_t version = 0;
  std::memcpy(&version, header + 4, 4);
  if (version == 1)
    fail(
        "{}: this is a binary glTF 1.0 file; bounce reads glTF 2.0 only (convert it, e.g. with "
        "Blender or gltf-pipeline)",
        path);
  uint32_t chunk_length = 0;
  std::memcpy(&chunk_length, header + 12, 4);
  // A chunk longer than the file is refused before anything is allocated for it (a fuzzed
  // 1 KB file claiming a 1 GiB chunk took 3 s and 1 GB to zero-fill before the read failed).
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in.tellg();
  in.seekg(20);
  if (std::memcmp(header + 16, "JSON", 4) != 0 || file_size < 20 ||
      std::streamoff(chunk_length) > file_size - 20)
    return {};
  std::string text(chunk_length, '\0');
  if (!in.read(text.data(), std::streamsize(chunk_length))) return {};
  return text;
}

// Keys whose value glTF 2.0 defines as an integer >= 0 (an index, count, offset or enum).
bool is_index_key(const std::string& key) {
  static const std::set<std::string> kKeys = {
      "buffer",        "bufferView", "byteLength", "byteOffset", "byteStride", "camera",
      "componentType", "count",      "index",      "indices",    "input",      "light",
      "material",      "mesh",       "mode",       "node",       "output",     "sampler",
      "scene",         "skin",       "source",     "texCoord"};
  return kKeys.count(key) > 0;
}

// Keys whose value is a number (or, for "scale", an array of numbers on a node).
bool is_number_key(const std::string& key) {
  static const std::set<std::string> kKeys = {"alphaCutoff",    "aspectRatio", "emissiveStrength",
                                              "innerConeAngle", "intensity",   "metallicFactor",
                                              "outerConeAngle", "range",       "roughnessFactor",
                                              "specularFactor", "strength",    "xmag",
                                              "ymag",           "yfov",        "zfar",
                                              "znear"};
  return kKeys.count(key) > 0;
}

bool is_number_array_key(const std::string& key) {
  static const std::set<std::string> kKeys = {
      "baseColorFactor",     "color",       "emissiveFactor", "matrix",
      "specularColorFactor", "translation", "weights"};
  return kKeys.count(key) > 0;
}

// Keys whose value glTF 2.0 defines as an array (of objects, or of indices for "children",
// "joints" and a scene's "nodes"); tinygltf skips any other shape without a word.
bool is_array_key(const std::string& key) {
  static const std::set<std::string> kKeys = {
      "accessors",      "animations", "bufferViews", "buffers",
      "cameras",        "channels",   "children",    "extensionsRequired",
      "extensionsUsed", "images",     "joints",      "materials",
      "meshes",         "nodes",      "primitives",  "samplers",
      "scenes",         "skins",      "targets",     "textures"};
  return kKeys.count(key) > 0;
}

bool all_numbers(const json& a) {
  if (!a.is_array()) return false;
  for (const json& v : a)
    if (!v.is_number()) return false;
  return true;
}

std::string shown(const json& v) {
  std::string text = v.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

// Warns once per value of the wrong type; tinygltf then uses the default in its place.
void check_types(const json& node, const std::string& pointer, const std::string& path,
                 int& warnings) {
  constexpr int kMaxWarnings = 20;
  if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i)
      check_types(node[i], pointer + "/" + std::to_string(i), path, warnings);
    return;
  }
  if (!node.is_object()) return;
  for (const auto& [key, value] : node.items()) {
    if (key == "extras") continue;  // the application's own data, any shape
    const std::string where = pointer + "/" + key;
    std::string expected;
    // A sparse accessor's "indices" is an object; everywhere else it is an accessor index.
    const bool sparse_indices = key == "indices" && value.is_object();
    if (is_index_key(key) && !sparse_indices &&
        !(value.is_number_integer() && value.get<int64_t>() >= 0))
      expected = "an integer >= 0";
    else if (key == "scale" && !value.is_number() && !all_numbers(value))
      expected = "a number";
    // A node's rotation is a quaternion, KHR_texture_transform's an angle.
    else if (key == "rotation" && !value.is_number() && !all_numbers(value))
      expected = "a number or an array of numbers";
    else if (is_number_key(key) && !value.is_number())
      expected = "a number";
    else if (is_number_array_key(key) && !all_numbers(value))
      expected = "an array of numbers";
    else if (is_array_key(key) && !value.is_array())
      expected = "an array";
    else if (key == "attributes" && value.is_object())
      for (const auto& [name, a] : value.items())
        if (!(a.is_number_integer() && a.get<int64_t>() >= 0) && ++warnings <= kMaxWarnings)
          warn(
              fmt::format("{}: {}/{} should be an accessor index (an integer >= 0), found {}; "
                          "the attribute is ignored",
                          path, where, name, shown(a)));
    if (!expected.empty()) {
      if (++warnings <= kMaxWarnings)
        warn(fmt::format("{}: {} should be {}, found {}; the default is used in its place", path,
                         where, expected, shown(value)));
      continue;
    }
    check_types(value, where, path, warnings);
  }
}

}  // namespace

void preflight(const std::string& path) {
  const std::string text = json_text(path);
  if (text.empty()) return;
  const json root = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!root.is_object()) return;  // not JSON at all: tinygltf's message says where
  const auto asset = root.find("asset");
  if (asset != root.end() && asset->is_object()) {
    const auto version = asset->find("version");
    if (version != asset->end() && version->is_string() &&
        !version->get<std::string>().starts_with("2."))
      fail(
          "{}: this is a glTF {} file; bounce reads glTF 2.0 only (convert it, e.g. with "
          "Blender or gltf-pipeline)",
          path, version->get<std::string>());
  } else if (root.contains("meshes") && root["meshes"].is_object()) {
    // glTF 1.0 keeps objects in dictionaries by name and often has no asset.version.
    fail("{}: this looks like a glTF 1.0 file (objects by name); bounce reads glTF 2.0 only", path);
  }
  const auto required = root.find("extensionsRequired");
  if (required != root.end() && required->is_array()) {
    std::vector<std::string> unsupported;
    for (const json& e : *required)
      if (e.is_string() && !kSupportedExtensions.count(e.get<std::string>()))
        unsupported.push_back(e.get<std::string>());
    if (!unsupported.empty())
      fail("{}: requires glTF extension(s) {} which bounce does not support", path,
           fmt::join(unsupported, ", "));
  }
  int warnings = 0;
  check_types(root, "", path, warnings);
  if (warnings > 20) warn(fmt::format("{}: {} more values of the wrong type", path, warnings - 20));
}

}  // namespace bounce::gltf
