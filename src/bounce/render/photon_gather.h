// Density estimation of indirect diffuse radiance from photons (seed 000 eq. 5.6) with the cone
// filter, k = 1, normalised as the thesis's notes §10 says it should be:
//   L(x) = albedo / pi * sum_p flux_p * w_p / ((1 - 2 / (3k)) * pi * r^2),  w_p = 1 - d_p / (k r)
// and no extra cosine (the photon density already carries it). A photon counts only if it
// arrived from the front of the surface, lies in the thin slab around x's tangent plane (seed
// 004's "sphere slice") and, when clearances exist, x is within its visibility polygon.
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/photon_clearance.h"
#include "bounce/render/photon_view.h"

namespace bounce {

struct GatherSettings {
  float radius = 0.05f;
  float slab = 0.005f;  // half-thickness of the accepted slab around the tangent plane
  bool clearance = true;
};

// Cone-filter weight of photon i at point x with normal n; 0 when the photon is rejected.
// Needs the decoded directions (PhotonBuffer::unpack_directions()).
BOUNCE_HD inline float gather_weight(const ConstPhotonView& photons, size_t i, vec3 x, vec3 n,
                                     const GatherSettings& s) {
  const vec3 d = photons.position[i] - x;
  const float dist2 = glm::dot(d, d);
  if (dist2 >= s.radius * s.radius) return 0.0f;
  if (std::abs(glm::dot(d, n)) > s.slab) return 0.0f;
  if (glm::dot(photons.incident_dir[i], n) >= 0.0f) return 0.0f;  // arrived from behind
  // The visibility polygon matters only beyond the photon's nearest obstacle.
  if (s.clearance && photons.clearance &&
      dist2 > photons.min_clearance[i] * photons.min_clearance[i] &&
      !within_clearance(x, photons.position[i], photons.normal_dir[i], photons.clearance_of(i)))
    return 0.0f;
  return 1.0f - std::sqrt(dist2) / s.radius;
}

// Turns the weighted flux sum at a point into outgoing radiance.
BOUNCE_HD inline vec3 cone_filter_radiance(vec3 weighted_flux, vec3 albedo, float radius) {
  constexpr float kConeNormalisation = 1.0f - 2.0f / 3.0f;  // k = 1
  return albedo * kInvPi * weighted_flux / (kConeNormalisation * kPi * radius * radius);
}

}  // namespace bounce
