#include <gtest/gtest.h>

#include "bounce/core/qmc.h"
#include "bounce/core/sampling.h"
#include "bounce/render/brdf.h"

namespace bounce {
namespace {

// Directional albedo: the integral of f * cos over the hemisphere, by cosine-weighted QMC.
vec3 directional_albedo(const SurfaceHit& s, vec3 wo, uint32_t n = 1 << 16) {
  vec3 sum(0.0f);
  for (uint32_t i = 0; i < n; ++i) {
    const vec3 wi = sample_cosine_hemisphere(sobol2(i));
    if (wi.z <= 0.0f) continue;
    sum += eval_brdf(s, wo, wi) * wi.z / cosine_hemisphere_pdf(wi.z);
  }
  return sum / float(n);
}

// The same with GGX importance sampling (needed for low roughness, where the lobe is narrow).
float ggx_albedo(float roughness, vec3 wo, uint32_t n = 1 << 17) {
  const float r = glm::max(roughness, kMinRoughness);
  const float alpha = r * r;
  double sum = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const vec3 h = sample_ggx_half_vector(sobol2(i), alpha);
    const vec3 wi = glm::reflect(-wo, h);
    if (wi.z <= 0.0f) continue;
    const float pdf =
        ggx_distribution(h.z * h.z, h.x * h.x + h.y * h.y, alpha) * h.z / (4.0f * glm::dot(wo, h));
    sum += ggx_specular(vec3(0, 0, 1), wo, wi, roughness, vec3(1.0f)).x * wi.z / pdf;
  }
  return float(sum / n);
}

TEST(Brdf, LambertWhiteFurnaceReflectsEverything) {
  // A white Lambertian surface under uniform unit radiance reflects radiance 1 in every direction.
  const SurfaceHit white{
      .normal = vec3(0, 0, 1), .albedo = vec3(1.0f), .f0 = vec3(0.0f), .roughness = 1.0f};
  for (float theta : {0.0f, 0.7f, 1.4f}) {
    const vec3 wo(std::sin(theta), 0.0f, std::cos(theta));
    const vec3 a = directional_albedo(white, wo);
    EXPECT_NEAR(a.x, 1.0f, 1e-3f);
    EXPECT_NEAR(a.z, 1.0f, 1e-3f);
  }
  const SurfaceHit grey{
      .normal = vec3(0, 0, 1), .albedo = vec3(0.5f), .f0 = vec3(0.0f), .roughness = 1.0f};
  EXPECT_NEAR(directional_albedo(grey, vec3(0, 0, 1)).y, 0.5f, 1e-3f);
}

TEST(Brdf, GgxAlbedoStaysWithinUnitInterval) {
  for (float roughness : {0.05f, 0.2f, 0.5f, 0.8f, 1.0f})
    for (float cos_o : {1.0f, 0.7f, 0.3f, 0.1f}) {
      const vec3 wo(std::sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
      const float a = ggx_albedo(roughness, wo);
      EXPECT_GE(a, 0.0f) << roughness << " " << cos_o;
      EXPECT_LE(a, 1.0f) << roughness << " " << cos_o;
      // Smooth, white-F0 surfaces seen head-on reflect nearly all light.
      if (roughness <= 0.2f && cos_o >= 0.7f) {
        EXPECT_GT(a, 0.85f) << roughness;
      }
    }
}

TEST(Brdf, GgxIsReciprocalAndZeroBelowHorizon) {
  const vec3 n(0, 0, 1), a = glm::normalize(vec3(0.3f, 0.1f, 0.8f)),
                         b = glm::normalize(vec3(-0.5f, 0.2f, 0.6f));
  const vec3 fab = ggx_specular(n, a, b, 0.4f, vec3(0.04f));
  const vec3 fba = ggx_specular(n, b, a, 0.4f, vec3(0.04f));
  EXPECT_NEAR(fab.x, fba.x, 1e-5f);
  EXPECT_EQ(ggx_specular(n, a, vec3(0.0f, 0.6f, -0.8f), 0.4f, vec3(0.04f)), vec3(0.0f));
  // Schlick's Fresnel: F0 at normal incidence, 1 at grazing.
  EXPECT_NEAR(fresnel_schlick(vec3(0.04f), 1.0f).x, 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_schlick(vec3(0.04f), 0.0f).x, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace bounce
