// Leak guard for density estimation. Each photon casts kClearanceRays short rays along its
// tangent plane and keeps the free distance of each. A gather point x sees photon p only if x is
// nearer to p (within p's tangent plane) than the smaller free distance of the two rays bounding
// x's direction. Visibility is symmetric, so this stands in for a ray from x to p, at a cost per
// photon instead of per photon and pixel. For a planar blocker it rejects everything behind it:
// a point behind the wall in direction theta is farther than the wall along both bounding rays'
// nearer one (or, if neither ray reaches the wall within the radius, farther than the radius).
#pragma once

#include <cmath>

#include "bounce/core/math.h"
#include "bounce/render/photons.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// Fills photons.clearance with free distances up to `radius`; returns the rays traced.
uint64_t compute_photon_clearance(const Tracer& tracer, float radius, PhotonBuffer& photons);

// Direction of clearance ray k in the photon's tangent frame.
inline vec3 clearance_direction(const Basis& frame, int k) {
  const float angle = kTwoPi * float(k) / float(kClearanceRays);
  return std::cos(angle) * frame.t + std::sin(angle) * frame.b;
}

// Whether gather point x is within photon p's visibility polygon. The sector is found with
// comparisons, not atan2: rays are 45 degrees apart.
static_assert(kClearanceRays == 8, "the sector lookup below assumes eight rays");
inline bool within_clearance(vec3 x, vec3 p, vec3 photon_normal, const float* clearance) {
  const Basis frame = Basis::from_normal(photon_normal);
  const vec3 d = x - p;
  const float a = glm::dot(d, frame.t), b = glm::dot(d, frame.b);
  const float planar2 = a * a + b * b;
  // Octant k holds angles [45k, 45(k+1)) degrees from the frame's t axis.
  int k;
  if (b >= 0.0f)
    k = a > 0.0f ? (b < a ? 0 : 1) : (b > -a ? 2 : 3);
  else
    k = a < 0.0f ? (b > a ? 4 : 5) : (-b > a ? 6 : 7);
  const float bound = glm::min(clearance[k], clearance[(k + 1) & 7]);
  return planar2 <= bound * bound;
}

}  // namespace bounce
