#include "bounce/scene/animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/matrix_decompose.hpp>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_limits.h"

namespace bounce {

namespace {

vec3 interpolate(const vec3& a, const vec3& b, float f) {
  return glm::mix(a, b, f);
}
quat interpolate(const quat& a, const quat& b, float f) {
  return glm::slerp(a, glm::dot(a, b) < 0.0f ? -b : b, f);
}

// Key values: translations, scales and camera positions within the scene extent (a scale beyond
// it would carry geometry beyond it), rotations finite and not zero.
bool valid_key(vec3 v) {
  return within_extent(v);
}
bool valid_key(const quat& q) {
  const float n = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  return std::isfinite(n) && n > 1e-12f;
}

template <typename T>
void check_keys(const Scene& s, const Keyframes<T>& k, const std::string& what) {
  if (k.times.size() != k.values.size())
    fail("{}: animation '{}': {} times but {} values", s.source, what, k.times.size(),
         k.values.size());
  for (size_t i = 0; i < k.times.size(); ++i) {
    if (!std::isfinite(k.times[i]) || k.times[i] < 0.0f)
      fail("{}: animation '{}': key time {} is negative or not finite", s.source, what, i);
    if (i > 0 && !(k.times[i] > k.times[i - 1]))
      fail("{}: animation '{}': key times must increase (key {} at {} s after {} s)", s.source,
           what, i, k.times[i], k.times[i - 1]);
    if (!valid_key(k.values[i]))
      fail(
          "{}: animation '{}': key {} (at {} s) has a value that is not finite or is outside the "
          "scene extent (|value| <= {:g})",
          s.source, what, i, k.times[i], kMaxSceneExtent);
  }
}

mat4 compose(const Animation& a, const std::vector<uint32_t>& tracks, float t) {
  mat4 m(1.0f);
  for (uint32_t k : tracks) m = m * a.tracks[k].delta(t);
  return m;
}

}  // namespace

template <typename T>
T Keyframes<T>::sample(float t) const {
  if (times.size() == 1 || t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  const size_t i = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  if (step) return values[i - 1];
  const float f = (t - times[i - 1]) / (times[i] - times[i - 1]);
  return interpolate(values[i - 1], values[i], f);
}

template struct Keyframes<vec3>;
template struct Keyframes<quat>;

mat4 TrsTrack::local(float t) const {
  const vec3 tr = translation.empty() ? rest_translation : translation.sample(t);
  const quat r = rotation.empty() ? rest_rotation : glm::normalize(rotation.sample(t));
  const vec3 s = scale.empty() ? rest_scale : scale.sample(t);
  return glm::translate(mat4(1.0f), tr) * glm::mat4_cast(r) * glm::scale(mat4(1.0f), s);
}

mat4 TrsTrack::delta(float t) const {
  return pivot * local(t) * glm::inverse(rest) * glm::inverse(pivot);
}

float TrsTrack::end_time() const {
  return std::max({translation.end_time(), rotation.end_time(), scale.end_time()});
}

float CameraPath::end_time() const {
  return std::max(position.end_time(), look_at.end_time());
}

Camera CameraPath::at(const Camera& base, float t) const {
  Camera c = base;
  if (!position.empty()) c.position = position.sample(t);
  if (!look_at.empty()) c.look_at = look_at.sample(t);
  return c;
}

Camera Animation::camera_at(const Camera& base, float t) const {
  if (camera_path.empty()) return base;
  const float d = duration();
  return camera_path.at(base, loop && d > 0.0f ? std::fmod(std::max(t, 0.0f), d) : t);
}

float Animation::duration() const {
  float d = camera_path.end_time();
  for (const auto& t : tracks) d = std::max(d, t.end_time());
  return d;
}

void Animation::append(Animation&& other, uint32_t mesh_base, uint32_t light_base, const mat4& m) {
  const uint32_t track_base = uint32_t(tracks.size());
  for (auto& t : other.tracks) {
    t.pivot = m * t.pivot;
    tracks.push_back(std::move(t));
  }
  for (auto& am : other.meshes) {
    am.mesh += mesh_base;
    for (auto& k : am.tracks) k += track_base;
    meshes.push_back(std::move(am));
  }
  for (auto& al : other.lights) {
    al.light += light_base;
    for (auto& k : al.tracks) k += track_base;
    lights.push_back(std::move(al));
  }
  if (camera_path.empty()) camera_path = std::move(other.camera_path);
  loop = loop && other.loop;
}

void prepare_animation(Scene& scene) {
  Animation& a = scene.animation;
  for (auto& t : a.tracks) {
    check_keys(scene, t.translation, t.name + "/translation");
    check_keys(scene, t.rotation, t.name + "/rotation");
    check_keys(scene, t.scale, t.name + "/scale");
    if (std::abs(glm::determinant(t.rest)) < 1e-12f || std::abs(glm::determinant(t.pivot)) < 1e-12f)
      fail("{}: animation '{}': its rest or parent transform is singular", scene.source, t.name);
    vec3 skew;
    vec4 perspective;
    glm::decompose(t.rest, t.rest_scale, t.rest_rotation, t.rest_translation, skew, perspective);
  }
  check_keys(scene, a.camera_path.position, "camera_path/position");
  check_keys(scene, a.camera_path.look_at, "camera_path/look_at");
  const auto check_tracks = [&](const std::vector<uint32_t>& tracks, const char* what,
                                uint32_t index) {
    for (uint32_t k : tracks)
      if (k >= a.tracks.size())
        fail("{}: animation of {} {} names track {}, which does not exist ({} tracks)",
             scene.source, what, index, k, a.tracks.size());
  };
  for (auto& am : a.meshes) {
    if (am.mesh >= scene.meshes.size())
      fail("{}: animation names mesh {}, which does not exist ({} meshes)", scene.source, am.mesh,
           scene.meshes.size());
    check_tracks(am.tracks, "mesh", am.mesh);
    am.rest_positions = scene.meshes[am.mesh].positions;
    am.rest_normals = scene.meshes[am.mesh].normals;
  }
  for (auto& al : a.lights) {
    if (al.light >= scene.lights.size())
      fail("{}: animation names light {}, which does not exist ({} lights)", scene.source, al.light,
           scene.lights.size());
    check_tracks(al.tracks, "light", al.light);
    al.rest_position = scene.lights[al.light].position;
    al.rest_direction = scene.lights[al.light].direction;
  }
}

SceneChange animate(Scene& scene, float t) {
  SceneChange change;
  Animation& a = scene.animation;
  if (a.empty()) return change;
  const float d = a.duration();
  t = a.loop && d > 0.0f ? std::fmod(std::max(t, 0.0f), d) : std::clamp(t, 0.0f, d);
  if (t == a.posed_time) return change;
  a.posed_time = t;
  for (const auto& am : a.meshes) {
    const mat4 m = compose(a, am.tracks, t);
    const mat3 nm = glm::transpose(glm::inverse(mat3(m)));
    Mesh& mesh = scene.meshes[am.mesh];
    // Normals and positions come from the rest copy, so no error builds up over frames. A
    // mirroring delta would flip winding; tracks are rotations and positive scales in practice.
    parallel_for(
        mesh.positions.size(),
        [&](size_t i) { mesh.positions[i] = vec3(m * vec4(am.rest_positions[i], 1.0f)); }, 4096);
    parallel_for(
        mesh.normals.size(),
        [&](size_t i) { mesh.normals[i] = glm::normalize(nm * am.rest_normals[i]); }, 4096);
    change.moved_meshes.push_back(am.mesh);
  }
  for (const auto& al : a.lights) {
    const mat4 m = compose(a, al.tracks, t);
    Light& l = scene.lights[al.light];
    l.position = vec3(m * vec4(al.rest_position, 1.0f));
    const vec3 dir = mat3(m) * al.rest_direction;
    if (glm::length(dir) > 0.0f) l.direction = glm::normalize(dir);
    change.lights = true;
  }
  std::sort(change.moved_meshes.begin(), change.moved_meshes.end());
  change.moved_meshes.erase(std::unique(change.moved_meshes.begin(), change.moved_meshes.end()),
                            change.moved_meshes.end());
  if (change.any()) scene.derive();
  return change;
}

}  // namespace bounce
