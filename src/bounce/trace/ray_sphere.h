// Ray against sphere: the one intersection test for sphere lights, used by the trace view and the
// Tracer's calls.
#pragma once

#include <cmath>
#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Distance along a unit-direction ray to the first crossing of the sphere's surface beyond
// tmin; infinity when there is none.
BOUNCE_HD inline float ray_sphere_distance_inline(vec3 centre, float radius, vec3 origin,
                                                  vec3 direction, float tmin) {
  const vec3 oc = centre - origin;
  const float b = glm::dot(oc, direction);
  const float disc = b * b - (glm::dot(oc, oc) - radius * radius);
  if (disc < 0.0f) return std::numeric_limits<float>::infinity();
  const float root = std::sqrt(disc);
  const float t = b - root > tmin ? b - root : b + root;
  return t > tmin ? t : std::numeric_limits<float>::infinity();
}

// The same, compiled once for the host: every host caller gets bit-identical distances, so a
// distance the Tracer reports can be compared exactly with one computed elsewhere.
float ray_sphere_distance(vec3 centre, float radius, vec3 origin, vec3 direction, float tmin);

}  // namespace bounce
