// Leak guard for density estimation. Each photon casts kClearanceRays short rays along its
// tangent plane and keeps the free distance of each. A gather point x sees photon p only if x is
// nearer to p (within p's tangent plane) than the smaller free distance of the two rays bounding
// x's direction. Visibility is symmetric, so this stands in for a ray from x to p, at a cost per
// photon instead of per photon and pixel. For a planar blocker it rejects everything behind it:
// a point behind the wall in direction theta is farther than the wall along both bounding rays'
// nearer one (or, if neither ray reaches the wall within the radius, farther than the radius).
//
// The per-photon bodies are below (clearance_frame and clearance_ray, store_clearance;
// photon_clearance whole, through the trace view, for a GPU backend); the CPU launcher hands a
// batch of photons' rays to the Tracer as one stream.
#pragma once

#include <cmath>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/photon_view.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

struct PhotonBuffer;
class Tracer;

// Fills photons.clearance (and min_clearance) with free distances up to `radius`; returns the
// rays traced. Needs photons.unpack_directions().
uint64_t compute_photon_clearance(const Tracer& tracer, float radius, PhotonBuffer& photons);

// Direction of clearance ray k in the photon's tangent frame.
BOUNCE_HD inline vec3 clearance_direction(const Basis& frame, int k) {
  const float angle = kTwoPi * float(k) / float(kClearanceRays);
  return std::cos(angle) * frame.t + std::sin(angle) * frame.b;
}

// Where photon i's clearance rays start (just above the surface, so they skim it instead of
// hitting it) and the tangent frame they fan out in.
struct ClearanceFrame {
  vec3 origin;
  Basis frame;
};
BOUNCE_HD inline ClearanceFrame clearance_frame(const PhotonView& photons, size_t i) {
  const vec3 normal = photons.normal_dir[i];
  return {offset_origin(photons.position[i], normal), Basis::from_normal(normal)};
}
// Clearance ray k, of length `radius`.
BOUNCE_HD inline Ray clearance_ray(const ClearanceFrame& f, int k, float radius) {
  return Ray{f.origin, 0.0f, clearance_direction(f.frame, k), radius};
}

// Free distance along a clearance ray that met `hit`: anything, a sphere light included, blocks.
BOUNCE_HD inline float clearance_distance(const Hit& hit, float radius) {
  return hit.any() ? hit.t : radius;
}

// Stores photon i's free distances and the smallest of them.
BOUNCE_HD inline void store_clearance(const PhotonView& photons, size_t i, const float* distance) {
  float* clearance = photons.clearance_of(i);
  float smallest = distance[0];
  for (int k = 0; k < kClearanceRays; ++k) {
    clearance[k] = distance[k];
    smallest = glm::min(smallest, distance[k]);
  }
  photons.min_clearance[i] = smallest;
}

// Photon i whole, through the trace view: the per-photon kernel.
BOUNCE_HD inline void photon_clearance(const TraceView& trace, const PhotonView& photons, size_t i,
                                       float radius) {
  const ClearanceFrame f = clearance_frame(photons, i);
  float distance[kClearanceRays];
  for (int k = 0; k < kClearanceRays; ++k)
    distance[k] = clearance_distance(trace.intersect(clearance_ray(f, k, radius)), radius);
  store_clearance(photons, i, distance);
}

// Whether gather point x is within photon p's visibility polygon. The sector is found with
// comparisons, not atan2: rays are 45 degrees apart.
static_assert(kClearanceRays == 8, "the sector lookup below assumes eight rays");
BOUNCE_HD inline bool within_clearance(vec3 x, vec3 p, vec3 photon_normal, const float* clearance) {
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
