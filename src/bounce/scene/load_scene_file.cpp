// The JSON scene file (*.bounce.json): models placed by transforms, lights and a camera.
// The format is documented in docs/scene-format.md. The reader is strict: unknown keys, wrong
// types, wrong array lengths, missing fields and non-finite numbers are errors naming the key
// and where it is, so that a typo cannot silently change the scene.
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string_view>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "bounce/core/error.h"
#include "bounce/scene/load.h"

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

// Loads one entry of "models" (a file or a built-in scene), not yet transformed.
Scene load_model(const Object& o, const std::string& file, const fs::path& dir) {
  if (o.has("file") == o.has("builtin"))
    fail("{}: {}: give exactly one of 'file' and 'builtin'", file, o.where());
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
  const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : dir / name;
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
                                                                 "intensity"};
  static const std::initializer_list<std::string_view> kSpot = {
      "type", "name", "position", "direction", "intensity", "inner_deg", "outer_deg"};
  static const std::initializer_list<std::string_view> kDirectional = {"type", "name", "direction",
                                                                       "irradiance"};
  static const std::initializer_list<std::string_view> kSphere = {"type", "name", "position",
                                                                  "radius", "radiance"};
  if (type == "point") return kPoint;
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

Light parse_light(const json& j, const std::string& file, const std::string& where) {
  if (!j.is_object()) fail("{}: {}: expected an object, found {}", file, where, j.type_name());
  if (!j.contains("type")) fail("{}: {}: missing required key 'type'", file, where);
  if (!j.at("type").is_string()) fail("{}: {}: 'type' must be a string", file, where);
  const std::string type = j.at("type").get<std::string>();
  if (type != "point" && type != "spot" && type != "directional" && type != "sphere")
    fail("{}: {}: unknown light type '{}' (point, spot, directional or sphere)", file, where, type);
  const Object o(j, file, where, light_keys(type));
  Light light;
  if (type == "point") {
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
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the file", path);
  std::ostringstream text;
  text << in.rdbuf();
  const json root = parse_json(text.str(), path);
  const Object top(root, path, "top level", {"models", "lights", "camera"});
  const fs::path dir = fs::path(path).parent_path();

  Scene scene;
  scene.source = path;
  bool camera_from_model = false;
  const json& models = array_or_empty(top, "models", path);
  for (size_t i = 0; i < models.size(); ++i) {
    const Object o(models[i], path, fmt::format("models[{}]", i),
                   {"file", "builtin", "translate", "rotate", "scale"});
    const mat4 m = model_transform(o, path);
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
    scene.append(std::move(model), m);
  }
  const json& lights = array_or_empty(top, "lights", path);
  for (size_t i = 0; i < lights.size(); ++i) {
    scene.lights.push_back(parse_light(lights[i], path, fmt::format("lights[{}]", i)));
  }
  if (top.has("camera")) {
    scene.camera = parse_camera(
        Object(top.at("camera"), path, "camera", {"position", "look_at", "up", "fov_deg"}), path);
    scene.has_camera = true;
  }
  return scene;
}

}  // namespace bounce
