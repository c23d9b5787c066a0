#include "bounce/interactive/flashlight.h"

#include "bounce/core/error.h"

namespace bounce {

Light make_flashlight(const Camera& camera, const FlashlightSettings& s) {
  const vec3 forward = glm::normalize(camera.look_at - camera.position);
  vec3 right = glm::cross(forward, camera.up);
  right = glm::length(right) > 1e-6f ? glm::normalize(right) : vec3(1.0f, 0.0f, 0.0f);
  const vec3 up = glm::cross(right, forward);
  const vec3 position =
      camera.position + s.offset.x * right + s.offset.y * up + s.offset.z * forward;
  Light l = Light::spot(position, forward, s.intensity, s.inner_deg, s.outer_deg);
  l.name = "flashlight";
  return l;
}

size_t add_flashlight(Scene& scene, const Camera& camera, const FlashlightSettings& settings) {
  scene.lights.push_back(make_flashlight(camera, settings));
  return scene.lights.size() - 1;
}

bool place_flashlight(Scene& scene, size_t index, const Camera& camera,
                      const FlashlightSettings& settings) {
  if (index >= scene.lights.size())
    fail("flashlight: light {} does not exist (the scene has {} lights)", index,
         scene.lights.size());
  const Light l = make_flashlight(camera, settings);
  Light& current = scene.lights[index];
  if (current == l) return false;
  current = l;
  return true;
}

}  // namespace bounce
