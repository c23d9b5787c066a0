// The surface BRDF of seed 000 §4.3: Lambert diffuse plus UE4-style GGX specular
// (GGX D, Schlick Fresnel, Schlick-GGX geometry with k = (roughness + 1)^2 / 8).
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/surface_hit.h"

namespace bounce {

// Below this, alpha = roughness^2 turns GGX into a near-delta that no light sample finds.
inline constexpr float kMinRoughness = 0.03f;

// GGX D from cos^2 and sin^2 of the half vector's angle. Taking sin^2 separately (not as
// 1 - cos^2) keeps D accurate for smooth surfaces, where float cancellation would ruin it.
BOUNCE_HD inline float ggx_distribution(float cos2_h, float sin2_h, float alpha) {
  const float a2 = alpha * alpha;
  const float d = sin2_h + cos2_h * a2;
  return a2 / (kPi * d * d);
}

BOUNCE_HD inline float schlick_ggx_g1(float n_dot_v, float k) {
  return n_dot_v / (n_dot_v * (1.0f - k) + k);
}

BOUNCE_HD inline vec3 fresnel_schlick(vec3 f0, float v_dot_h) {
  const float m = 1.0f - glm::clamp(v_dot_h, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

// The GGX specular BRDF value (without the cosine) for unit wo (to the viewer) and wi (to the
// light) whose cosines n_dot_l and n_dot_v are both positive; with others it may be inf or NaN.
// Branch-free, so that a row loop over pixels vectorises it (light_lane.h).
BOUNCE_HD inline vec3 ggx_specular_front(vec3 n, vec3 wo, vec3 wi, float n_dot_l, float n_dot_v,
                                         float roughness, vec3 f0) {
  const vec3 h = glm::normalize(wi + wo);
  const float r = glm::max(roughness, kMinRoughness);
  const float alpha = r * r;
  const float k = (r + 1.0f) * (r + 1.0f) / 8.0f;
  const float n_dot_h = glm::max(glm::dot(n, h), 0.0f);
  const vec3 across = glm::cross(n, h);
  const float d = ggx_distribution(n_dot_h * n_dot_h, glm::dot(across, across), alpha);
  const float g = schlick_ggx_g1(n_dot_l, k) * schlick_ggx_g1(n_dot_v, k);
  return fresnel_schlick(f0, glm::dot(wo, h)) * (d * g / (4.0f * n_dot_l * n_dot_v));
}

// GGX specular BRDF value (without the cosine) for unit wo (to the viewer) and wi (to the light).
BOUNCE_HD inline vec3 ggx_specular(vec3 n, vec3 wo, vec3 wi, float roughness, vec3 f0) {
  const float n_dot_l = glm::dot(n, wi);
  const float n_dot_v = glm::dot(n, wo);
  if (n_dot_l <= 0.0f || n_dot_v <= 0.0f) return vec3(0.0f);
  return ggx_specular_front(n, wo, wi, n_dot_l, n_dot_v, roughness, f0);
}

BOUNCE_HD inline vec3 lambert(vec3 albedo) {
  return albedo * kInvPi;
}

// Full BRDF: Lambert + GGX, as the seed sums them (no energy exchange between the lobes).
BOUNCE_HD inline vec3 eval_brdf(const SurfaceHit& s, vec3 wo, vec3 wi) {
  if (glm::dot(s.normal, wi) <= 0.0f) return vec3(0.0f);
  vec3 f = lambert(s.albedo);
  if (max_component(s.f0) > 0.0f) f += ggx_specular(s.normal, wo, wi, s.roughness, s.f0);
  return f;
}

}  // namespace bounce
