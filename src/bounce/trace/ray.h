// Rays and what they hit: the records every ray query takes and returns, host and device alike.
#pragma once

#include <cstdint>
#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct Ray {
  vec3 origin{0.0f};
  float tmin = 0.0f;
  vec3 direction{0.0f, 0.0f, 1.0f};
  float tmax = std::numeric_limits<float>::infinity();
};

// The closest thing along a ray: a triangle (mesh and triangle within it), a sphere light, or
// nothing. Sphere lights are geometry for every query (they stop paths and block shadow rays)
// but have no surface: such a hit has `light` set and no mesh.
struct Hit {
  static constexpr uint32_t kNone = 0xFFFFFFFFu;
  float t = std::numeric_limits<float>::infinity();
  uint32_t mesh = kNone;
  uint32_t triangle = 0;
  vec2 barycentric{0.0f};  // weights of the triangle's vertices 1 and 2
  uint32_t light = kNone;  // index into the scene's lights when the ray ended on a sphere light

  // A triangle was hit.
  BOUNCE_HD bool valid() const { return mesh != kNone; }
  BOUNCE_HD bool sphere_light() const { return light != kNone; }
  // Anything was hit.
  BOUNCE_HD bool any() const { return valid() || sphere_light(); }
};

}  // namespace bounce
