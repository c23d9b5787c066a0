// Warping of uniform samples in [0,1)^2 to directions and points, each with its pdf.
#pragma once

#include <cmath>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Uniform direction on the unit sphere (seed 000 eq. 5.1-5.2); pdf 1 / (4 pi) per steradian.
BOUNCE_HD inline vec3 sample_uniform_sphere(vec2 u) {
  const float z = 1.0f - 2.0f * u.y;
  const float r = std::sqrt(glm::max(0.0f, 1.0f - z * z));
  const float phi = kTwoPi * u.x;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
BOUNCE_HD inline float uniform_sphere_pdf() {
  return 1.0f / (4.0f * kPi);
}

// Cosine-weighted direction around +z (Malley's method, seed 000 eq. 5.3-5.4); pdf cos / pi.
BOUNCE_HD inline vec3 sample_cosine_hemisphere(vec2 u) {
  const float r = std::sqrt(u.x);
  const float phi = kTwoPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(glm::max(0.0f, 1.0f - u.x))};
}
BOUNCE_HD inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f;
}

// Uniform direction in the cone of half-angle acos(cos_max) around +z; pdf 1 / solid angle.
BOUNCE_HD inline vec3 sample_uniform_cone(vec2 u, float cos_max) {
  const float cos_theta = 1.0f - u.x * (1.0f - cos_max);
  const float sin_theta = std::sqrt(glm::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = kTwoPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}
BOUNCE_HD inline float uniform_cone_pdf(float cos_max) {
  return 1.0f / (kTwoPi * (1.0f - cos_max));
}

// Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2; pdf 1 / area.
// Uses the square-root parameterisation, which keeps a stratified input stratified.
BOUNCE_HD inline vec2 sample_uniform_triangle(vec2 u) {
  const float su = std::sqrt(u.x);
  return {su * (1.0f - u.y), su * u.y};
}

// Uniform point on the unit disk by Shirley and Chiu's concentric map; pdf 1 / pi.
BOUNCE_HD inline vec2 sample_concentric_disk(vec2 u) {
  const vec2 o = 2.0f * u - 1.0f;
  if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = (kPi / 2.0f) - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * vec2(std::cos(theta), std::sin(theta));
}

// GGX (Trowbridge-Reitz) normal distribution sampling around +z with alpha = roughness^2;
// returns the half vector, whose pdf is D(h) * cos(theta_h).
BOUNCE_HD inline vec3 sample_ggx_half_vector(vec2 u, float alpha) {
  const float a2 = alpha * alpha;
  const float cos2 = (1.0f - u.x) / (1.0f + (a2 - 1.0f) * u.x);
  const float cos_theta = std::sqrt(glm::max(0.0f, cos2));
  const float sin_theta = std::sqrt(glm::max(0.0f, 1.0f - cos2));
  const float phi = kTwoPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

}  // namespace bounce
