// The flashlight: a spot light the camera carries. The viewer adds it to the scene's lights
// while it is on and moves it with the camera every frame.
#pragma once

#include "bounce/scene/camera.h"
#include "bounce/scene/light.h"

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

}  // namespace bounce
