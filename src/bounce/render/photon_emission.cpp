#include "bounce/render/photon_emission.h"

#include <algorithm>

namespace bounce {

PhotonEmitters PhotonEmitters::from(const Scene& scene) {
  PhotonEmitters e;
  e.picker = LightPicker::build(scene);
  e.scene_centre = scene.bounds.centre();
  e.scene_radius = std::max(0.5f * scene.bounds.diagonal(), 1e-3f);
  e.environment_map = scene.environment_map;
  for (const Light& l : scene.lights) e.total_power += l.power(e.scene_radius);
  for (const AreaLight& a : scene.area_lights) e.total_power += a.power();
  return e;
}

}  // namespace bounce
