// The flashlight: a spot light the camera carries. The viewer, render, bench and sequence add it
// to the scene's lights and move it with the camera every frame (place_flashlight).
#pragma once

#include <cstddef>

#include "bounce/scene/camera.h"
#include "bounce/scene/light.h"
#include "bounce/scene/scene.h"

namespace bounce {

struct FlashlightSettings {
  vec3 intensity{3.0f, 2.8f, 2.5f};  // W/sr on the axis
  float inner_deg = 12.0f;
  float outer_deg = 25.0f;
  // Offset from the eye in camera space (right, up, forward), metres: a light held a little
  // below the eye casts visible shadows instead of hiding them behind what it lights.
  vec3 offset{0.0f, -0.05f, 0.0f};
};

// The spot light for a camera; named "flashlight".
Light make_flashlight(const Camera& camera, const FlashlightSettings& settings);

// Appends the flashlight for `camera` to the scene's lights and returns its index there.
size_t add_flashlight(Scene& scene, const Camera& camera, const FlashlightSettings& settings);

// Moves the flashlight at `index` in the scene's lights to `camera` (and to the settings, when
// they were edited). Returns whether it changed: the renderer then has to hear that the lights
// changed (SceneChange::lights).
bool place_flashlight(Scene& scene, size_t index, const Camera& camera,
                      const FlashlightSettings& settings);

}  // namespace bounce
