// glTF 2.0 (.gltf and .glb) through tinygltf.
//
// What is read: the default scene's node tree (TRS or matrix transforms), TRIANGLES primitives
// (indexed or not) with POSITION, NORMAL and TEXCOORD_0; metallic-roughness materials with
// KHR_materials_emissive_strength and KHR_materials_specular; KHR_lights_punctual; the first
// perspective camera; node animations (translation, rotation and scale channels of every
// animation in the file, played together) as TrsTracks. tinygltf parses the JSON and the GLB
// container; every index, count and byte range it hands over is checked before use
// (gltf_buffers.cpp), since a broken file must give an error, never an out-of-bounds read.
//
// This file reads the file and runs the conversion steps, each in its own file (gltf_internal.h).
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/input_file.h"
#include "bounce/scene/gltf_internal.h"
#include "bounce/scene/load.h"

namespace bounce {

namespace gltf {

const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular",
    "KHR_texture_transform"};

namespace {

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// tinygltf's image callback. Images stored in a bufferView are left for later: tinygltf passes a
// pointer into the buffer without checking the view's range, so they are decoded only after
// texture_for_image (gltf_materials.cpp) has checked it. An image that cannot be decoded is not an
// error: the material falls back to its base colour factor.
bool decode_image(tg::Image* image, const int index, std::string* err, std::string* warnings,
                  int width, int height, const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  std::string error;
  if (bytes == nullptr || size <= 0 ||
      !tg::LoadImageData(image, index, &error, warnings, width, height, bytes, size, nullptr)) {
    if (warnings) *warnings += "image " + std::to_string(index) + " cannot be decoded\n";
    image->image.clear();
  }
  return true;
}

bool is_glb(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::memcmp(magic, "glTF", 4) == 0;
}

void forward_warnings(const std::string& warnings, const std::string& path) {
  std::istringstream lines(warnings);
  std::string line;
  while (std::getline(lines, line))
    if (!trim(line).empty()) warn(path + ": " + trim(line));
}

// tinygltf's file access for external buffers and images, without opening anything but regular
// files: its own FileExists opens the file, which blocks forever on a fifo.
bool file_exists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}
bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user_data) {
  if (exists_but_not_regular(path)) {
    if (err) *err += "'" + path + "' is not a regular file (a device, fifo or directory)\n";
    return false;
  }
  return tg::ReadWholeFile(out, err, path, user_data);
}

tg::Model read_model(const std::string& path) {
  check_regular_file(path, "glTF file");
  preflight(path);
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail("{}: cannot open the file", path);
  }
  tg::TinyGLTF loader;
  loader.SetImageLoader(&decode_image, nullptr);
  loader.SetFsCallbacks(
      {&file_exists, &tg::ExpandFilePath, &read_whole_file, &tg::WriteWholeFile, nullptr});
  tg::Model model;
  std::string error, warnings;
  const bool ok = is_glb(path) ? loader.LoadBinaryFromFile(&model, &error, &warnings, path)
                               : loader.LoadASCIIFromFile(&model, &error, &warnings, path);
  if (!ok) {
    error = trim(error);
    if (error.empty()) error = trim(warnings);
    // nlohmann's "[json.exception.parse_error.101] " prefix says nothing to a user.
    if (const size_t end = error.find("] ");
        error.starts_with("[json.") && end != std::string::npos)
      error = error.substr(end + 2);
    fail("{}: cannot load glTF: {}", path, error.empty() ? "unknown error" : error);
  }
  forward_warnings(warnings, path);
  std::vector<std::string> unsupported;
  for (const auto& e : model.extensionsRequired)
    if (!kSupportedExtensions.count(e)) unsupported.push_back(e);
  if (!unsupported.empty())
    fail("{}: requires glTF extension(s) {} which bounce does not support", path,
         fmt::join(unsupported, ", "));
  return model;
}

}  // namespace

}  // namespace gltf

Scene load_gltf(const std::string& path) {
  const gltf::tg::Model model = gltf::read_model(path);
  Scene scene;
  scene.source = path;
  gltf::Context ctx{path, model, scene};
  ctx.material_of.assign(model.materials.size(), -1);
  gltf::walk_nodes(ctx);
  gltf::read_animations(ctx);
  if (!ctx.ignored.empty())
    warn(fmt::format("{}: ignoring unsupported glTF features: {}", path,
                     fmt::join(ctx.ignored, ", ")));
  return scene;
}

}  // namespace bounce
