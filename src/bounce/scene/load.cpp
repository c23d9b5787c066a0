// Scene specs: built-in names and files dispatched by extension.
#include "bounce/scene/load.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <memory>
#include <string_view>
#include <system_error>

#include "bounce/core/error.h"
#include "bounce/scene/quake/load_quake.h"

namespace bounce {

namespace {

constexpr const char* kAcceptedForms =
    "a scene is 'cornell', 'cubes:N', 'cubes:N:SEED', 'leak', a .obj, .gltf, .glb, .bsp or "
    ".bounce.json (.json) file, or a Quake 3 map in an archive (ARCHIVE.pk3:maps/NAME.bsp)";

// More cubes than this would need several GiB; a typo such as an extra zero should not do that.
constexpr uint32_t kMaxCubes = 10'000'000;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix.data(), suffix.size()) == 0;
}

// Parses a whole string of decimal digits (no sign, no spaces) into a uint32.
bool parse_u32(std::string_view text, uint32_t* out) {
  if (text.empty() ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *out);
  return ec == std::errc() && end == text.data() + text.size();
}

Scene make_cubes_from_spec(const std::string& spec) {
  const std::string_view rest = std::string_view(spec).substr(std::string_view("cubes").size());
  if (rest.empty() || rest.front() != ':' || rest.size() == 1)
    fail("{}: the cube count is missing; write cubes:N or cubes:N:SEED with N a positive integer",
         spec);
  const std::string_view args = rest.substr(1);
  const size_t colon = args.find(':');
  const std::string_view count_text = args.substr(0, colon);
  uint32_t count = 0;
  if (!parse_u32(count_text, &count) || count == 0)
    fail("{}: the cube count '{}' is not a positive integer (cubes:N or cubes:N:SEED)", spec,
         count_text);
  if (count > kMaxCubes) fail("{}: at most {} cubes are supported", spec, kMaxCubes);
  uint32_t seed = 1;
  if (colon != std::string_view::npos) {
    const std::string_view seed_text = args.substr(colon + 1);
    if (!parse_u32(seed_text, &seed))
      fail("{}: the seed '{}' is not an unsigned 32-bit integer (cubes:N:SEED)", spec, seed_text);
  }
  return make_cubes(count, seed);
}

enum class FileKind { kObj, kGltf, kSceneFile, kUnknown };

FileKind file_kind(const std::string& path) {
  const std::string name = lower(std::filesystem::path(path).filename().string());
  if (ends_with(name, ".obj")) return FileKind::kObj;
  if (ends_with(name, ".gltf") || ends_with(name, ".glb")) return FileKind::kGltf;
  if (ends_with(name, ".json")) return FileKind::kSceneFile;  // includes .bounce.json
  return FileKind::kUnknown;
}

void check_file_exists(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    fail("{}: no such file or built-in scene; {}", path, kAcceptedForms);
  if (std::filesystem::is_directory(status))
    fail("{}: is a directory, not a scene file; {}", path, kAcceptedForms);
}

}  // namespace

bool is_builtin_scene(const std::string& spec) {
  return spec == "cornell" || spec == "leak" || spec == "cubes" || spec.starts_with("cubes:");
}

Scene make_builtin_scene(const std::string& spec) {
  if (spec == "cornell") return make_cornell();
  if (spec == "leak") return make_leak();
  if (spec == "cubes" || spec.starts_with("cubes:")) return make_cubes_from_spec(spec);
  fail("{}: not a built-in scene; {}", spec, kAcceptedForms);
}

Scene load_model_file(const std::string& path) {
  if (quake::is_quake_spec(path)) return quake::load_quake_map(path).scene;
  switch (file_kind(path)) {
    case FileKind::kObj:
      return load_obj(path);
    case FileKind::kGltf:
      return load_gltf(path);
    case FileKind::kSceneFile:
      fail("{}: a scene file cannot be used as a model (only .obj, .gltf and .glb)", path);
    case FileKind::kUnknown:
      break;
  }
  fail("{}: unknown model file type (expected .obj, .gltf, .glb, .bsp or ARCHIVE.pk3:MAP.bsp)",
       path);
}

bool add_default_environment(Scene& scene) {
  if (!scene.lights.empty() || !scene.area_lights.empty()) return false;
  warn(fmt::format(
      "{}: the scene has no lights; lighting it with a default sky (radiance {:g} above the "
      "horizon, {:g} below): add lights, or an environment light, to the scene file to choose",
      scene.source, kDefaultSkyRadiance, kDefaultGroundRadiance));
  // A map of two rows, the upper and the lower hemisphere: light from above and less from
  // below, so tops, sides and undersides of a model read apart.
  Image image(1, 2);
  image.at(0, 0) = vec3(kDefaultSkyRadiance);
  image.at(0, 1) = vec3(kDefaultGroundRadiance);
  scene.environment_map =
      std::make_shared<const EnvironmentMap>(EnvironmentMap::from_image(image, "default sky"));
  Light sky = Light::environment(vec3(1.0f));
  sky.name = "default sky";
  scene.lights.push_back(sky);
  scene.derive();
  return true;
}

Scene load_scene(const std::string& spec) {
  if (spec.empty()) fail("empty scene name; {}", kAcceptedForms);
  if (is_builtin_scene(spec)) {
    Scene scene = make_builtin_scene(spec);
    scene.source = spec;
    return scene;
  }
  if (quake::is_quake_spec(spec)) {
    Scene scene = quake::load_quake_map(spec).scene;
    scene.source = spec;
    scene.finalize();
    add_default_environment(scene);
    return scene;
  }
  const FileKind kind = file_kind(spec);
  if (kind == FileKind::kUnknown) fail("{}: unknown scene type; {}", spec, kAcceptedForms);
  check_file_exists(spec);
  Scene scene = kind == FileKind::kSceneFile ? load_scene_file(spec) : load_model_file(spec);
  scene.source = spec;
  scene.finalize();
  add_default_environment(scene);
  return scene;
}

}  // namespace bounce
