// Vector math shared by every module: glm types plus the few helpers the renderer needs.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "bounce/core/device.h"

namespace bounce {

using glm::ivec2;
using glm::ivec3;
using glm::mat3;
using glm::mat4;
using glm::uvec2;
using glm::uvec3;
using glm::vec2;
using glm::vec3;
using glm::vec4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kTwoPi = 6.28318530717958647692f;

BOUNCE_HD inline float max_component(vec3 v) {
  return glm::max(v.x, glm::max(v.y, v.z));
}
BOUNCE_HD inline bool is_finite(vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
BOUNCE_HD inline float sqr(float x) {
  return x * x;
}

// Orthonormal basis around a unit vector n (Duff et al. 2017, "Building an orthonormal basis,
// revisited"): branch-free and exact for every n.
struct Basis {
  vec3 t, b, n;

  BOUNCE_HD static Basis from_normal(vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    return {vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x),
            vec3(c, sign + n.y * n.y * a, -n.y), n};
  }
  BOUNCE_HD vec3 to_world(vec3 local) const { return local.x * t + local.y * b + local.z * n; }
  BOUNCE_HD vec3 to_local(vec3 world) const {
    return {glm::dot(world, t), glm::dot(world, b), glm::dot(world, n)};
  }
};

// Offsets a ray origin along the geometric normal so that the new ray does not hit the surface it
// starts on; the offset scales with the coordinates' magnitude to stay above float rounding.
BOUNCE_HD inline vec3 offset_origin(vec3 p, vec3 geometric_normal_towards_ray) {
  const float scale = 1e-4f * (1.0f + max_component(glm::abs(p)));
  return p + geometric_normal_towards_ray * scale;
}

}  // namespace bounce
