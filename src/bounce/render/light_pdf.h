// The solid-angle pdfs that match light_sampling.h's samplers, for weighting a direction found by
// another strategy (BSDF sampling) with multiple importance sampling.
#pragma once

#include <cmath>

#include "bounce/core/math.h"
#include "bounce/scene/light.h"
#include "bounce/scene/scene.h"

namespace bounce {

// pdf with which sample_sphere_light(light, p, .) returns any direction inside the cone the
// sphere subtends from p (uniform in that cone); 0 when p is inside the sphere.
inline float sphere_light_pdf(const Light& light, vec3 p) {
  const vec3 to_centre = light.position - p;
  const float d2 = glm::dot(to_centre, to_centre);
  const float r2 = light.radius * light.radius;
  if (d2 <= r2) return 0.0f;
  const float sin2_max = r2 / d2;
  const float cos_max = std::sqrt(1.0f - sin2_max);
  return 1.0f / (kTwoPi * (sin2_max / (1.0f + cos_max)));
}

// pdf with which sample_area_light(scene, light, p, .) returns the direction towards a point of
// the light at `distance` from p whose emitting face makes cosine `cos_light` with the direction
// back to p: the sampler is uniform over the light's area, so this is distance^2 / (cos * area).
inline float area_light_pdf(const AreaLight& light, float distance, float cos_light) {
  if (cos_light <= 0.0f || light.area <= 0.0f) return 0.0f;
  return distance * distance / (cos_light * light.area);
}

}  // namespace bounce
