// Where photon paths start: every light (point, spot, directional, sphere, emissive triangles),
// chosen in proportion to power by the same LightPicker the path tracer uses.
#pragma once

#include <cstdint>

#include "bounce/core/math.h"
#include "bounce/render/light_picker.h"
#include "bounce/scene/scene.h"

namespace bounce {

struct EmittedPhoton {
  vec3 origin;
  vec3 direction;
  vec3 flux;  // W carried by the path
};

struct PhotonEmitters {
  LightPicker picker;  // entries: Scene::lights, then Scene::area_lights
  vec3 total_power{0.0f};
  float scene_radius = 0.0f;  // covers the scene, for directional lights
  vec3 scene_centre{0.0f};

  static PhotonEmitters from(const Scene& scene);
  bool empty() const { return picker.empty(); }
};

// Emits path i of n: u (stratified over the paths) picks the light and the point on it, v (random)
// the direction. Flux is normalised so that the paths' expected total equals the lights' power.
EmittedPhoton emit_photon(const Scene& scene, const PhotonEmitters& emitters, vec2 u, vec2 v,
                          uint32_t path_count);

}  // namespace bounce
