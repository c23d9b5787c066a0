// The cone of directions in which a sphere is seen from a point outside it: sampled by
// sample_sphere_light (light_sampling.h) and weighted by sphere_light_pdf (light_pdf.h), which
// must agree on it exactly.
#pragma once

#include <cmath>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct SphereCone {
  bool outside = false;        // false: the point is inside the sphere and sees no cone
  float cos_max = 1.0f;        // cosine of the cone's half-angle
  float one_minus_cos = 0.0f;  // 1 - cos_max, without the cancellation of a small sphere

  BOUNCE_HD float solid_angle() const { return kTwoPi * one_minus_cos; }
};

// d2: squared distance from the point to the sphere's centre; r2: the squared radius.
BOUNCE_HD inline SphereCone sphere_cone(float d2, float r2) {
  if (d2 <= r2) return {};
  const float sin2_max = r2 / d2;
  const float cos_max = std::sqrt(1.0f - sin2_max);
  // 1 - cos = sin^2 / (1 + cos): no difference of nearly equal numbers.
  return {true, cos_max, sin2_max / (1.0f + cos_max)};
}

}  // namespace bounce
