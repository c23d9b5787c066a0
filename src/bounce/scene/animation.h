// Animation of a scene: keyframed translation, rotation and scale tracks that move meshes and
// lights, and a camera path for playback. Meshes stay in world space (what the tracer and every
// technique read); animate() rewrites the moved meshes' vertices from their rest copies.
//
// A track moves what it drives by delta(t) = pivot * TRS(t) * inverse(rest) * inverse(pivot):
// `rest` is the local transform the geometry was baked with, `pivot` the world transform of the
// track's parent. Something driven by several tracks (a glTF node under an animated node) moves
// by the product of their deltas, outermost first, which equals the composed node transforms.
#pragma once

#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "bounce/core/math.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/light.h"
#include "bounce/scene/scene_change.h"

namespace bounce {

using quat = glm::quat;

// Values at increasing times; linear interpolation (spherical for rotations) or steps, clamped
// at both ends.
template <typename T>
struct Keyframes {
  std::vector<float> times;  // seconds, strictly increasing
  std::vector<T> values;
  bool step = false;

  bool empty() const { return times.empty(); }
  float end_time() const { return times.empty() ? 0.0f : times.back(); }
  T sample(float t) const;
};

struct TrsTrack {
  std::string name;
  mat4 pivot{1.0f};
  mat4 rest{1.0f};
  // The value of a channel without keys is the rest transform's own (decomposed at prepare()).
  Keyframes<vec3> translation;
  Keyframes<quat> rotation;
  Keyframes<vec3> scale;
  vec3 rest_translation{0.0f};
  quat rest_rotation{1.0f, 0.0f, 0.0f, 0.0f};
  vec3 rest_scale{1.0f};

  mat4 local(float t) const;  // TRS(t)
  mat4 delta(float t) const;  // pivot * TRS(t) * inverse(rest) * inverse(pivot)
  float end_time() const;
};

struct AnimatedMesh {
  uint32_t mesh = 0;
  std::vector<uint32_t> tracks;  // outermost first
  // Captured by Animation::prepare from the scene as loaded.
  std::vector<vec3> rest_positions;
  std::vector<vec3> rest_normals;
};

struct AnimatedLight {
  uint32_t light = 0;
  std::vector<uint32_t> tracks;  // outermost first
  vec3 rest_position{0.0f};
  vec3 rest_direction{0.0f, -1.0f, 0.0f};
};

// Camera keyframes for playback in the viewer (`camera_path` of the scene file).
struct CameraPath {
  Keyframes<vec3> position;
  Keyframes<vec3> look_at;
  bool empty() const { return position.empty(); }
  float end_time() const;
  Camera at(const Camera& base, float t) const;  // base gives up and field of view
};

struct Animation {
  std::vector<TrsTrack> tracks;
  std::vector<AnimatedMesh> meshes;
  std::vector<AnimatedLight> lights;
  CameraPath camera_path;
  bool loop = true;          // times past the end wrap around
  float posed_time = -1.0f;  // the time animate() last posed the scene at (-1: never)

  bool empty() const { return tracks.empty(); }
  float duration() const;  // the longest track, seconds
  // The camera at time t: on the camera path (wrapping around when the animation loops), or
  // `base` when there is no path.
  Camera camera_at(const Camera& base, float t) const;
  // Shifts mesh and light indices and moves pivots by `m` when a scene is appended to another.
  void append(Animation&& other, uint32_t mesh_base, uint32_t light_base, const mat4& m);
};

struct Scene;

// Checks the animation against the scene (indices, key counts, increasing times; throws Error
// naming scene.source) and captures the rest geometry. Scene::finalize calls it.
void prepare_animation(Scene& scene);

// Poses the scene at time t (seconds): rewrites moved meshes and lights, re-derives area lights
// and bounds, and returns what changed. Cheap when nothing is animated.
SceneChange animate(Scene& scene, float t);

}  // namespace bounce
