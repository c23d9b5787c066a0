// The range of values a scene may hold, whatever loader or edit produced it. docs/reliability.md
// gives the reasons; in short, the tracer works in single-precision floats.
#pragma once

#include <cmath>

#include "bounce/core/math.h"

namespace bounce {

// Largest |coordinate| of any vertex, point-like light, camera or animation key, in metres. A
// float's spacing at 1e6 is 6 cm, about as coarse as a surface can be and still be lit without
// visible self-shadowing; Embree refuses rays with coordinates beyond about 1.8e18 (it asserts).
inline constexpr float kMaxSceneExtent = 1e6f;

// Largest emitted value (intensity, irradiance or radiance) per channel. A light's power, this
// times up to 4 pi^2 r^2 with r up to kMaxSceneExtent, then stays far below float's 3.4e38, and so
// do the sums over many lights that pick lights by power.
inline constexpr float kMaxEmission = 1e20f;

// True when every coordinate is finite and within kMaxSceneExtent (NaN fails the comparison).
inline bool within_extent(vec3 p) {
  return std::abs(p.x) <= kMaxSceneExtent && std::abs(p.y) <= kMaxSceneExtent &&
         std::abs(p.z) <= kMaxSceneExtent;
}

// True when every channel is finite, not negative and at most kMaxEmission.
inline bool valid_emission(vec3 c) {
  return c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f && c.x <= kMaxEmission && c.y <= kMaxEmission &&
         c.z <= kMaxEmission;
}

}  // namespace bounce
