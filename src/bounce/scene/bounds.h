// Axis-aligned bounding box.
#pragma once

#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct Bounds {
  vec3 lo{std::numeric_limits<float>::infinity()};
  vec3 hi{-std::numeric_limits<float>::infinity()};

  BOUNCE_HD void extend(vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  BOUNCE_HD bool empty() const { return lo.x > hi.x; }
  BOUNCE_HD vec3 centre() const { return 0.5f * (lo + hi); }
  BOUNCE_HD float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

}  // namespace bounce
