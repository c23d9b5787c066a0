// The JSON scene file (*.bounce.json): models placed by transforms, lights, a camera and
// keyframed animation of models, lights and the camera.
// The format is documented in docs/scene-format.md. The reader is strict: unknown keys, wrong
// types, wrong array lengths, missing fields and non-finite numbers are errors naming the key
// and where it is, so that a typo cannot silently change the scene.
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <string_view>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "bounce/core/error.h"
#include "bounce/core/input_file.h"
#include "bounce/scene/load.h"
#include "bounce/scene/quake/load_quake.h"

namespace bounce {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// One JSON object of the file with the keys it may have, and typed, checked access to them.
class Object {
 public:
  Object(const json& j, const std::string& file, std::string where,
         std::initializer_list<std::string_view> allowed)
      : j_(j), file_(file), where_(std::move(where)) {
    if (!j.is_object()) fail("{}: {}: expected an object, found {}", file_, where_, j.type_name());
    for (const auto& [key, value] : j.items()) {
      bool known = false;
      for (std::string_view a : allowed) known |= key == a;
      if (!known)
        fail("{}: {}: unknown key '{}' (allowed: {})", file_, where_, key,
             fmt::join(allowed, ", "));
    }
  }

  bool has(const char* key) const { return j_.contains(key); }
  const json& at(const char* key) const {
    if (!has(key)) fail("{}: {}: missing required key '{}'", file_, where_, key);
    return j_.at(key);
  }

  double number(const char* key) const { return to_number(at(key), key); }
  double number_or(const char* key, double fallback) const {
    return has(key) ? number(key) : fallback;
  }
  std::string string(const char* key) const {
    const json& v = at(key);
    if (!v.is_string())
      fail("{}: {}: '{}' must be a string, found {}", file_, where_, key, v.type_name());
    return v.get<std::string>();
  }
  vec3 vector(const char* key) const { return to_vec3(at(key), key, false); }
  vec3 vector_or(const char* key, vec3 fallback) const { return has(key) ? vector(key) : fallback; }
  // A colour or scale: [x, y, z], or one number for all three.
  vec3 triple(const char* key) const { return to_vec3(at(key), key, true); }
  vec3 triple_or(const char* key, vec3 fallback) const { return has(key) ? triple(key) : fallback; }

  bool boolean(const char* key) const {
    const json& v = at(key);
    if (!v.is_boolean())
      fail("{}: {}: '{}' must be true or false, found {}", file_, where_, key, v.type_name());
    return v.get<bool>();
  }

  const std::string& where() const { return where_; }

 private:
  double to_number(const json& v, const char* key) const {
    if (!v.is_number())
      fail("{}: {}: '{}' must be a number, found {}", file_, where_, key, v.type_name());
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail("{}: {}: '{}' is not a finite number", file_, where_, key);
    return x;
  }
  vec3 to_vec3(const json& v, const char* key, bool allow_scalar) const {
    if (allow_scalar && v.is_number()) return vec3(float(to_number(v, key)));
    if (!v.is_array() || v.size() != 3)
      fail("{}: {}: '{}' must be an array of 3 numbers{}", file_, where_, key,
           allow_scalar ? " or a number" : "");
    vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = float(to_number(v[size_t(i)], key));
    return out;
  }

  const json& j_;
  const std::string& file_;
  std::string where_;
};

// Parses JSON text, turning nlohmann's errors into ours and refusing duplicate keys (nlohmann
// would silently keep the last one).
json parse_json(const std::string& text, const std::string& file) {
  std::vector<std::vector<std::string>> keys;  // the keys seen in each open object
  auto callback = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) keys.emplace_back();
    if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == json::parse_event_t::key && !keys.empty()) {
      const std::string key = parsed.get<std::string>();
      for (const auto& k : keys.back())
        if (k == key) fail("{}: duplicate key '{}'", file, key);
      keys.back().push_back(key);
    }
    return true;
  };
  try {
    return json::parse(text, callback);
  } catch (const json::exception& e) {
    std::string message = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix; keep "parse error at line...".
    if (const size_t end = message.find("] ");
        message.starts_with("[json.") && end != std::string::npos)
      message = message.substr(end + 2);
    fail("{}: invalid JSON: {}", file, message);
  }
}

// translate * rotate_z * rotate_y * rotate_x * scale: scale first, then the rotations about the
// fixed x, y and z axes in that order (degrees), then the translation.
mat4 model_transform(const Object& o, const std::string& file) {
  const vec3 t = o.vector_or("translate", vec3(0.0f));
  const vec3 r = o.vector_or("rotate", vec3(0.0f));
  const vec3 s = o.triple_or("scale", vec3(1.0f));
  if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f)
    fail("{}: {}: 'scale' must not be zero", file, o.where());
  mat4 m = glm::translate(mat4(1.0f), t);
  m = glm::rotate(m, glm::radians(r.z), vec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(r.y), vec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(r.x), vec3(1, 0, 0));
  return glm::scale(m, s);
}

vec3 non_zero_direction(const Object& o, const std::string& file);

// The rotation of model_transform (Rz * Ry * Rx, degrees) as a quaternion.
quat euler_quat(vec3 degrees) {
  return glm::angleAxis(glm::radians(degrees.z), vec3(0, 0, 1)) *
         glm::angleAxis(glm::radians(degrees.y), vec3(0, 1, 0)) *
         glm::angleAxis(glm::radians(degrees.x), vec3(1, 0, 0));
}

// The shortest rotation turning unit vector a into unit vector b.
quat turn(vec3 a, vec3 b) {
  const float c = glm::dot(a, b);
  if (c < -1.0f + 1e-6f) {  // opposite: half a turn about any axis perpendicular to a
    vec3 axis = glm::cross(vec3(1, 0, 0), a);
    if (glm::length(axis) < 1e-3f) axis = glm::cross(vec3(0, 1, 0), a);
    return glm::angleAxis(kPi, glm::normalize(axis));
  }
  const vec3 axis = glm::cross(a, b);
  return glm::normalize(quat(1.0f + c, axis.x, axis.y, axis.z));
}

// The "keys" array and "interpolation" of an animation object: the keys' objects (checked for
// allowed keys), their times (finite, >= 0, strictly increasing) and whether they step.
struct KeyList {
  std::vector<Object> keys;
  std::vector<float> times;
  bool step = false;
};

KeyList parse_keys(const json& j, const std::string& file, const std::string& where,
                   std::initializer_list<std::string_view> anim_keys,
                   std::initializer_list<std::string_view> key_keys) {
  const Object o(j, file, where, anim_keys);
  KeyList out;
  if (o.has("interpolation")) {
    const std::string mode = o.string("interpolation");
    if (mode != "linear" && mode != "step")
      fail("{}: {}: 'interpolation' must be \"linear\" or \"step\", found \"{}\"", file, where,
           mode);
    out.step = mode == "step";
  }
  const json& keys = o.at("keys");
  if (!keys.is_array())
    fail("{}: {}: 'keys' must be an array, found {}", file, where, keys.type_name());
  if (keys.empty()) fail("{}: {}: 'keys' needs at least one key", file, where);
  out.keys.reserve(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    out.keys.emplace_back(keys[k], file, fmt::format("{}.keys[{}]", where, k), key_keys);
    const Object& key = out.keys.back();
    const double time = key.number("time");
    if (time < 0.0) fail("{}: {}: 'time' must not be negative, found {}", file, key.where(), time);
    if (k > 0 && !(float(time) > out.times.back()))
      fail("{}: {}: 'time' must be greater than the previous key's ({} s), found {} s", file,
           key.where(), out.times.back(), time);
    out.times.push_back(float(time));
  }
  return out;
}

template <typename T>
void add_key(Keyframes<T>& k, float time, const T& value, bool step) {
  k.times.push_back(time);
  k.values.push_back(value);
  k.step = step;
}

// A model's "animation": a track that moves the model from its static transform `rest`.
TrsTrack parse_model_animation(const Object& model, const std::string& file, const mat4& rest) {
  const std::string where = model.where() + ".animation";
  const KeyList list = parse_keys(model.at("animation"), file, where, {"keys", "interpolation"},
                                  {"time", "translate", "rotate", "scale"});
  const vec3 static_scale = model.triple_or("scale", vec3(1.0f));
  const bool static_mirrors = static_scale.x * static_scale.y * static_scale.z < 0.0f;
  TrsTrack track;
  track.name = model.where();
  track.rest = rest;
  for (size_t k = 0; k < list.keys.size(); ++k) {
    const Object& key = list.keys[k];
    const float t = list.times[k];
    if (!key.has("translate") && !key.has("rotate") && !key.has("scale"))
      fail("{}: {}: a key needs at least one of 'translate', 'rotate' and 'scale'", file,
           key.where());
    if (key.has("translate")) add_key(track.translation, t, key.vector("translate"), list.step);
    if (key.has("rotate")) add_key(track.rotation, t, euler_quat(key.vector("rotate")), list.step);
    if (key.has("scale")) {
      const vec3 s = key.triple("scale");
      if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f)
        fail("{}: {}: 'scale' must not be zero", file, key.where());
      if ((s.x * s.y * s.z < 0.0f) != static_mirrors)
        fail("{}: {}: 'scale' must mirror exactly when the model's static 'scale' does", file,
             key.where());
      add_key(track.scale, t, s, list.step);
    }
  }
  // Channels without keys hold the static transform's values, given exactly (rather than
  // decomposed from `rest`, which cannot tell a mirroring scale from a rotation).
  const float t0 = list.times.front();
  if (track.translation.empty())
    add_key(track.translation, t0, model.vector_or("translate", vec3(0.0f)), list.step);
  if (track.rotation.empty())
    add_key(track.rotation, t0, euler_quat(model.vector_or("rotate", vec3(0.0f))), list.step);
  if (track.scale.empty()) add_key(track.scale, t0, static_scale, list.step);
  return track;
}

// Puts track k first in the track lists of entries[first_entry...] (AnimatedMesh or
// AnimatedLight, naming their mesh or light by `item`) and gives the items in [base, end) that
// have no entry yet one with track k alone.
template <typename Entry>
void prepend_track(std::vector<Entry>& entries, size_t first_entry, uint32_t Entry::*item,
                   uint32_t base, uint32_t end, uint32_t k) {
  std::vector<char> done(end - base, 0);
  for (size_t e = first_entry; e < entries.size(); ++e) {
    entries[e].tracks.insert(entries[e].tracks.begin(), k);
    const uint32_t i = entries[e].*item;  // range checked later by prepare_animation
    if (i >= base && i < end) done[i - base] = 1;
  }
  for (uint32_t i = base; i < end; ++i) {
    if (done[i - base]) continue;
    Entry entry;
    entry.*item = i;
    entry.tracks = {k};
    entries.push_back(std::move(entry));
  }
}

// A light's "animation": keyed positions (and directions for spot and directional lights) as a
// track whose rest is the light's static position, so that its delta carries the rest position
// onto the keyed one and turns the rest direction into the keyed one.
TrsTrack parse_light_animation(const Object& o, const Light& light, const std::string& file) {
  const std::string where = o.where() + ".animation";
  const bool has_position = light.type != LightType::kDirectional;
  const bool has_direction =
      light.type == LightType::kSpot || light.type == LightType::kDirectional;
  static const std::initializer_list<std::string_view> kPositioned = {"time", "position"};
  static const std::initializer_list<std::string_view> kAimed = {"time", "position", "direction"};
  static const std::initializer_list<std::string_view> kDirected = {"time", "direction"};
  const KeyList list = parse_keys(o.at("animation"), file, where, {"keys", "interpolation"},
                                  !has_direction ? kPositioned
                                  : has_position ? kAimed
                                                 : kDirected);
  TrsTrack track;
  track.name = o.where();
  track.rest = glm::translate(mat4(1.0f), light.position);
  const vec3 rest_direction = glm::normalize(light.direction);
  for (size_t k = 0; k < list.keys.size(); ++k) {
    const Object& key = list.keys[k];
    const float t = list.times[k];
    if (!key.has("position") && !key.has("direction"))
      fail("{}: {}: a key needs '{}'", file, key.where(),
           has_position && has_direction ? "position' or 'direction"
           : has_position                ? "position"
                                         : "direction");
    if (key.has("position")) add_key(track.translation, t, key.vector("position"), list.step);
    if (key.has("direction")) {
      const vec3 d = non_zero_direction(key, file);
      add_key(track.rotation, t, turn(rest_direction, glm::normalize(d)), list.step);
    }
  }
  return track;
}

// A Quake 3 map model: "file" is ARCHIVE.pk3:maps/NAME.bsp or a .bsp file (paths relative to
// the scene file), "archives" more .pk3 files for textures, "patch_level" and "spawn" as in
// quake::QuakeOptions.
template <typename Resolve>
Scene load_map_model(const Object& o, const std::string& file, Resolve resolve) {
  const std::string name = o.string("file");
  quake::QuakeOptions options;
  if (o.has("archives")) {
    const json& list = o.at("archives");
    if (!list.is_array())
      fail("{}: {}: 'archives' must be an array of .pk3 file names", file, o.where());
    for (const json& a : list) {
      if (!a.is_string() || a.get<std::string>().empty())
        fail("{}: {}: 'archives' must be an array of .pk3 file names", file, o.where());
      options.archives.push_back(resolve(a.get<std::string>()).string());
    }
  }
  const auto whole = [&](const char* key, int lo, int hi, int fallback) {
    if (!o.has(key)) return fallback;
    const double v = o.number(key);
    if (v != std::floor(v) || v < lo || v > hi)
      fail("{}: {}: '{}' must be a whole number in [{}, {}]", file, o.where(), key, lo, hi);
    return int(v);
  };
  options.patch_level = whole("patch_level", 1, 64, options.patch_level);
  options.spawn = whole("spawn", 0, 1 << 20, 0);
  // The archive (or .bsp) part of the spec is relative to the scene file like any file.
  const std::string lower_name = [&] {
    std::string l = name;
    for (char& c : l) c = char(std::tolower(static_cast<unsigned char>(c)));
    return l;
  }();
  const size_t at = lower_name.rfind(".pk3:");
  const std::string spec = at == std::string::npos
                               ? resolve(name).string()
                               : resolve(name.substr(0, at + 4)).string() + name.substr(at + 4);
  try {
    return quake::load_quake_map(spec, options).scene;
  } catch (const Error& e) {
    fail("{}: {}: {}", file, o.where(), e.what());
  }
}

// Loads one entry of "models" (a file or a built-in scene), not yet transformed.
Scene load_model(const Object& o, const std::string& file, const fs::path& dir) {
  if (o.has("file") == o.has("builtin"))
    fail("{}: {}: give exactly one of 'file' and 'builtin'", file, o.where());
  const bool is_map = o.has("file") && quake::is_quake_spec(o.string("file"));
  for (const char* key : {"archives", "patch_level", "spawn"})
    if (o.has(key) && !is_map)
      fail("{}: {}: '{}' applies only to Quake 3 maps (ARCHIVE.pk3:maps/NAME.bsp or .bsp)", file,
           o.where(), key);
  if (o.has("builtin")) {
    const std::string name = o.string("builtin");
    if (!is_builtin_scene(name))
      fail("{}: {}: '{}' is not a built-in scene (cornell, cubes:N, cubes:N:SEED, leak)", file,
           o.where(), name);
    try {
      return make_builtin_scene(name);
    } catch (const Error& e) {
      fail("{}: {}: {}", file, o.where(), e.what());
    }
  }
  const std::string name = o.string("file");
  if (name.empty()) fail("{}: {}: 'file' is empty", file, o.where());
  const auto resolve = [&](const std::string& n) {
    return fs::path(n).is_absolute() ? fs::path(n) : dir / n;
  };
  if (quake::is_quake_spec(name)) return load_map_model(o, file, resolve);
  const fs::path path = resolve(name);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    fail("{}: {}: model file '{}' not found (looked for {})", file, o.where(), name, path.string());
  try {
    return load_model_file(path.string());
  } catch (const Error& e) {
    fail("{}: {}: {}", file, o.where(), e.what());
  }
}

// The keys each light type may have; any other key (say "colour" for "intensity") is an error.
std::initializer_list<std::string_view> light_keys(const std::string& type) {
  static const std::initializer_list<std::string_view> kPoint = {"type", "name", "position",
                                                                 "intensity", "animation"};
  static const std::initializer_list<std::string_view> kSpot = {
      "type", "name", "position", "direction", "intensity", "inner_deg", "outer_deg", "animation"};
  static const std::initializer_list<std::string_view> kDirectional = {"type", "name", "direction",
                                                                       "irradiance", "animation"};
  static const std::initializer_list<std::string_view> kSphere = {
      "type", "name", "position", "radius", "radiance", "animation"};
  static const std::initializer_list<std::string_view> kEnvironment = {
      "type", "name", "radiance", "intensity", "map", "rotation_deg"};
  if (type == "point") return kPoint;
  if (type == "environment") return kEnvironment;
  if (type == "spot") return kSpot;
  if (type == "directional") return kDirectional;
  return kSphere;
}

vec3 non_zero_direction(const Object& o, const std::string& file) {
  const vec3 d = o.vector("direction");
  if (!(glm::length(d) > 0.0f)) fail("{}: {}: 'direction' must not be zero", file, o.where());
  return d;
}

vec3 non_negative(const Object& o, const char* key, const std::string& file) {
  const vec3 v = o.triple(key);
  if (glm::any(glm::lessThan(v, vec3(0.0f))))
    fail("{}: {}: '{}' must not be negative", file, o.where(), key);
  return v;
}

// An environment light: a sky of `radiance` (default white) times `intensity` (default 1), or
// an equirectangular map (.exr or .hdr, relative to the scene file) multiplied by both, turned
// by rotation_deg about +y. The map goes to `map`.
Light parse_environment(const Object& o, const std::string& file, const fs::path& dir,
                        std::shared_ptr<const EnvironmentMap>* map) {
  const vec3 radiance = o.has("radiance") ? non_negative(o, "radiance", file) : vec3(1.0f);
  const double intensity = o.number_or("intensity", 1.0);
  if (!(intensity >= 0.0)) fail("{}: {}: 'intensity' must not be negative", file, o.where());
  const double rotation = o.number_or("rotation_deg", 0.0);
  if (!std::isfinite(rotation)) fail("{}: {}: 'rotation_deg' must be finite", file, o.where());
  if (o.has("map")) {
    const std::string name = o.string("map");
    const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : dir / name;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
      fail("{}: {}: environment map '{}' not found (looked for {})", file, o.where(), name,
           path.string());
    try {
      *map = std::make_shared<const EnvironmentMap>(EnvironmentMap::load(path.string()));
    } catch (const Error& e) {
      fail("{}: {}: {}", file, o.where(), e.what());
    }
  }
  return Light::environment(radiance * float(intensity), float(rotation));
}

// Parses one light; a light with an "animation" also gets its track into `track`, an environment
// light's map goes to `map`.
Light parse_light(const json& j, const std::string& file, const std::string& where, TrsTrack* track,
                  bool* animated, const fs::path& dir, std::shared_ptr<const EnvironmentMap>* map) {
  if (!j.is_object()) fail("{}: {}: expected an object, found {}", file, where, j.type_name());
  if (!j.contains("type")) fail("{}: {}: missing required key 'type'", file, where);
  if (!j.at("type").is_string()) fail("{}: {}: 'type' must be a string", file, where);
  const std::string type = j.at("type").get<std::string>();
  if (type != "point" && type != "spot" && type != "directional" && type != "sphere" &&
      type != "environment")
    fail("{}: {}: unknown light type '{}' (point, spot, directional, sphere or environment)", file,
         where, type);
  const Object o(j, file, where, light_keys(type));
  Light light;
  if (type == "environment") {
    light = parse_environment(o, file, dir, map);
  } else if (type == "point") {
    light = Light::point(o.vector("position"), non_negative(o, "intensity", file));
  } else if (type == "spot") {
    const float inner = float(o.number_or("inner_deg", 0.0));
    const float outer = float(o.number_or("outer_deg", 45.0));
    if (!(inner >= 0.0f && inner < outer && outer <= 90.0f))
      fail("{}: {}: need 0 <= inner_deg < outer_deg <= 90 (got {} and {})", file, where, inner,
           outer);
    light = Light::spot(o.vector("position"), non_zero_direction(o, file),
                        non_negative(o, "intensity", file), inner, outer);
  } else if (type == "directional") {
    light = Light::directional(non_zero_direction(o, file), non_negative(o, "irradiance", file));
  } else {
    const float radius = float(o.number("radius"));
    if (!(radius > 0.0f)) fail("{}: {}: 'radius' must be positive", file, where);
    light = Light::sphere(o.vector("position"), radius, non_negative(o, "radiance", file));
  }
  light.name = o.has("name") ? o.string("name") : where;
  *animated = o.has("animation");
  if (*animated) *track = parse_light_animation(o, light, file);
  return light;
}

Camera parse_camera(const Object& o, const std::string& file) {
  Camera c;
  c.position = o.vector("position");
  c.look_at = o.vector("look_at");
  c.up = o.vector_or("up", vec3(0.0f, 1.0f, 0.0f));
  c.vfov_deg = float(o.number_or("fov_deg", 45.0));
  if (!(c.vfov_deg > 0.0f && c.vfov_deg < 180.0f))
    fail("{}: camera: 'fov_deg' must be in (0, 180), got {}", file, c.vfov_deg);
  if (glm::length(c.look_at - c.position) <= 0.0f)
    fail("{}: camera: 'look_at' equals 'position'", file);
  if (!(glm::length(glm::cross(c.look_at - c.position, c.up)) > 0.0f))
    fail("{}: camera: 'up' must not be zero or parallel to the view direction", file);
  return c;
}

// The array under `key` of the top-level object, or an empty one.
const json& array_or_empty(const Object& top, const char* key, const std::string& file) {
  static const json empty = json::array();
  if (!top.has(key)) return empty;
  const json& a = top.at(key);
  if (!a.is_array()) fail("{}: '{}' must be an array, found {}", file, key, a.type_name());
  return a;
}

}  // namespace

Scene load_scene_file(const std::string& path) {
  check_regular_file(path, "scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the file", path);
  std::ostringstream text;
  text << in.rdbuf();
  const json root = parse_json(text.str(), path);
  const Object top(root, path, "top level", {"models", "lights", "camera", "camera_path", "loop"});
  const fs::path dir = fs::path(path).parent_path();

  Scene scene;
  scene.source = path;
  bool camera_from_model = false;
  const json& models = array_or_empty(top, "models", path);
  for (size_t i = 0; i < models.size(); ++i) {
    const Object o(models[i], path, fmt::format("models[{}]", i),
                   {"file", "builtin", "translate", "rotate", "scale", "animation", "archives",
                    "patch_level", "spawn"});
    const mat4 m = model_transform(o, path);
    const bool animated = o.has("animation");
    TrsTrack track;
    if (animated) track = parse_model_animation(o, path, m);
    Scene model = load_model(o, path, dir);
    // Without a camera of its own the file takes the first model's camera, moved with it.
    if (!camera_from_model && model.has_camera) {
      camera_from_model = true;
      scene.camera.position = vec3(m * vec4(model.camera.position, 1.0f));
      scene.camera.look_at = vec3(m * vec4(model.camera.look_at, 1.0f));
      scene.camera.up = mat3(m) * model.camera.up;
      scene.camera.vfov_deg = model.camera.vfov_deg;
      scene.has_camera = true;
    }
    const uint32_t mesh_base = uint32_t(scene.meshes.size());
    const uint32_t light_base = uint32_t(scene.lights.size());
    const size_t animated_mesh_base = scene.animation.meshes.size();
    const size_t animated_light_base = scene.animation.lights.size();
    scene.append(std::move(model), m);
    if (animated) {
      // The model's track is outermost: it goes first in the track lists of all its meshes and
      // lights, before the tracks the model brought (a glTF file's node animations).
      Animation& a = scene.animation;
      const uint32_t k = uint32_t(a.tracks.size());
      a.tracks.push_back(std::move(track));
      prepend_track(a.meshes, animated_mesh_base, &AnimatedMesh::mesh, mesh_base,
                    uint32_t(scene.meshes.size()), k);
      prepend_track(a.lights, animated_light_base, &AnimatedLight::light, light_base,
                    uint32_t(scene.lights.size()), k);
    }
  }
  const json& lights = array_or_empty(top, "lights", path);
  int environments = 0;
  for (size_t i = 0; i < lights.size(); ++i) {
    TrsTrack track;
    bool animated = false;
    std::shared_ptr<const EnvironmentMap> map;
    scene.lights.push_back(
        parse_light(lights[i], path, fmt::format("lights[{}]", i), &track, &animated, dir, &map));
    if (scene.lights.back().type == LightType::kEnvironment) {
      if (environments++ > 0)
        fail("{}: lights[{}]: a second environment light; a scene has at most one", path, i);
      scene.environment_map = std::move(map);
    }
    if (animated) {
      AnimatedLight al;
      al.light = uint32_t(scene.lights.size() - 1);
      al.tracks = {uint32_t(scene.animation.tracks.size())};
      scene.animation.tracks.push_back(std::move(track));
      scene.animation.lights.push_back(std::move(al));
    }
  }
  if (top.has("camera")) {
    scene.camera = parse_camera(
        Object(top.at("camera"), path, "camera", {"position", "look_at", "up", "fov_deg"}), path);
    scene.has_camera = true;
  }
  if (top.has("camera_path")) {
    const KeyList list = parse_keys(top.at("camera_path"), path, "camera_path",
                                    {"keys", "interpolation"}, {"time", "position", "look_at"});
    CameraPath& cp = scene.animation.camera_path;
    cp = CameraPath{};
    for (size_t k = 0; k < list.keys.size(); ++k) {
      const Object& key = list.keys[k];
      const vec3 position = key.vector("position");
      const vec3 look_at = key.vector("look_at");
      if (!(glm::length(look_at - position) > 0.0f))
        fail("{}: {}: 'look_at' equals 'position'", path, key.where());
      add_key(cp.position, list.times[k], position, list.step);
      add_key(cp.look_at, list.times[k], look_at, list.step);
    }
  }
  scene.animation.loop = top.has("loop") ? top.boolean("loop") : true;
  return scene;
}

}  // namespace bounce
