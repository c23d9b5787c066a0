// Axis-aligned bounding box.
#pragma once

#include <limits>

#include "bounce/core/math.h"

namespace bounce {

struct Bounds {
  vec3 lo{std::numeric_limits<float>::infinity()};
  vec3 hi{-std::numeric_limits<float>::infinity()};

  void extend(vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x; }
  vec3 centre() const { return 0.5f * (lo + hi); }
  float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

}  // namespace bounce
