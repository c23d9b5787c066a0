// Importance sampling of the Lambert + GGX BRDF of brdf.h: one lobe is picked with a probability
// from the lobes' estimated reflectance, then a cosine-weighted (diffuse) or GGX half-vector
// (specular) direction; the pdf is always the mixture of both, so that MIS and the estimator see
// one strategy. Plain functions over plain data, for the path tracer and (later) CUDA kernels.
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/sampling.h"
#include "bounce/render/brdf.h"

namespace bounce {

// Probability of sampling the specular lobe at s seen from wo: the lobes' reflectance estimates
// (mean diffuse albedo; mean Schlick Fresnel at the view angle) relative to their sum.
BOUNCE_HD inline float specular_lobe_probability(const SurfaceHit& s, vec3 wo) {
  if (max_component(s.f0) <= 0.0f) return 0.0f;
  const vec3 fresnel = fresnel_schlick(s.f0, glm::dot(s.normal, wo));
  const float specular = (fresnel.x + fresnel.y + fresnel.z) / 3.0f;
  const float diffuse = (s.albedo.x + s.albedo.y + s.albedo.z) / 3.0f;
  if (specular + diffuse <= 0.0f) return 0.0f;
  return specular / (specular + diffuse);
}

// The GGX alpha that brdf.h evaluates with (roughness clamped to kMinRoughness, squared).
BOUNCE_HD inline float ggx_alpha(float roughness) {
  return sqr(glm::max(roughness, kMinRoughness));
}

// Solid-angle pdf of reflecting wo into wi by a half vector drawn from D(h) cos(theta_h).
BOUNCE_HD inline float ggx_reflection_pdf(vec3 n, vec3 wo, vec3 wi, float alpha) {
  const vec3 sum = wo + wi;
  const float len2 = glm::dot(sum, sum);
  if (len2 <= 0.0f) return 0.0f;
  const vec3 h = sum / glm::sqrt(len2);
  const float n_dot_h = glm::dot(n, h);
  const float wo_dot_h = glm::dot(wo, h);
  if (n_dot_h <= 0.0f || wo_dot_h <= 0.0f) return 0.0f;
  const vec3 across = glm::cross(n, h);
  return ggx_distribution(n_dot_h * n_dot_h, glm::dot(across, across), alpha) * n_dot_h /
         (4.0f * wo_dot_h);
}

// Solid-angle pdf with which sample_bsdf returns wi (the mixture over both lobes).
BOUNCE_HD inline float bsdf_pdf(const SurfaceHit& s, vec3 wo, vec3 wi) {
  const float cos_i = glm::dot(s.normal, wi);
  if (cos_i <= 0.0f) return 0.0f;
  const float p_spec = specular_lobe_probability(s, wo);
  float pdf = (1.0f - p_spec) * cos_i * kInvPi;
  if (p_spec > 0.0f) pdf += p_spec * ggx_reflection_pdf(s.normal, wo, wi, ggx_alpha(s.roughness));
  return pdf;
}

struct BsdfSample {
  vec3 wi{0.0f};
  vec3 f{0.0f};      // BRDF value for (wo, wi)
  float pdf = 0.0f;  // mixture pdf of wi; 0 when no direction was produced

  BOUNCE_HD bool valid() const { return pdf > 0.0f && max_component(f) > 0.0f; }
};

// Draws wi from the mixture: u_lobe picks the lobe, u the direction within it.
BOUNCE_HD inline BsdfSample sample_bsdf(const SurfaceHit& s, vec3 wo, float u_lobe, vec2 u) {
  BsdfSample b;
  const Basis basis = Basis::from_normal(s.normal);
  const float p_spec = specular_lobe_probability(s, wo);
  if (u_lobe < p_spec) {
    const vec3 h = basis.to_world(sample_ggx_half_vector(u, ggx_alpha(s.roughness)));
    const float wo_dot_h = glm::dot(wo, h);
    if (wo_dot_h <= 0.0f) return b;
    b.wi = 2.0f * wo_dot_h * h - wo;
  } else {
    b.wi = basis.to_world(sample_cosine_hemisphere(u));
  }
  const float len2 = glm::dot(b.wi, b.wi);
  if (!(len2 > 0.0f)) return b;
  b.wi /= glm::sqrt(len2);
  if (glm::dot(s.normal, b.wi) <= 0.0f) return b;
  b.pdf = bsdf_pdf(s, wo, b.wi);
  b.f = eval_brdf(s, wo, b.wi);
  return b;
}

// Veach's power heuristic (beta = 2) for two strategies with pdfs a (this one) and b.
BOUNCE_HD inline float power_heuristic(float a, float b) {
  if (!(a > 0.0f)) return 0.0f;
  if (!(b > 0.0f)) return 1.0f;
  const float r = b / a;
  return 1.0f / (1.0f + r * r);
}

}  // namespace bounce
