// The cone a sphere subtends: its solid angle against the closed form in double precision,
// including spheres so small or far that 1 - cos in float would cancel to nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bounce/render/light_pdf.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/sphere_cone.h"

namespace bounce {
namespace {

TEST(SphereCone, SolidAngleMatchesTheClosedForm) {
  for (const double ratio : {0.9, 0.5, 0.1, 1e-2, 1e-3, 1e-4}) {  // radius / distance
    const double d = 3.0, r = ratio * d;
    const SphereCone cone = sphere_cone(float(d * d), float(r * r));
    ASSERT_TRUE(cone.outside) << ratio;
    const double cos_max = std::sqrt(1.0 - ratio * ratio);
    // 2 pi (1 - cos), written without cancellation in double as well.
    const double solid_angle = 2.0 * std::numbers::pi * ratio * ratio / (1.0 + cos_max);
    EXPECT_NEAR(cone.cos_max, cos_max, 1e-6) << ratio;
    EXPECT_NEAR(cone.solid_angle(), solid_angle, 1e-5 * solid_angle) << ratio;
  }
  // The naive 1 - cos in float is 0 for this sphere; the cone still has its small solid angle.
  const SphereCone tiny = sphere_cone(1.0f, 1e-8f);
  EXPECT_EQ(1.0f - tiny.cos_max, 0.0f);
  EXPECT_NEAR(tiny.solid_angle(), std::numbers::pi * 1e-8, 1e-6 * std::numbers::pi * 1e-8);
}

TEST(SphereCone, APointInsideOrOnTheSphereSeesNoCone) {
  EXPECT_FALSE(sphere_cone(0.25f, 1.0f).outside);
  EXPECT_FALSE(sphere_cone(1.0f, 1.0f).outside);
  EXPECT_EQ(sphere_cone(0.25f, 1.0f).solid_angle(), 0.0f);
}

TEST(SphereCone, SamplerAndPdfUseTheSameCone) {
  // A far, small light: every sample's pdf is one over the cone's solid angle, and so is the
  // pdf that multiple importance sampling asks for.
  const Light light = Light::sphere(vec3(0.0f, 50.0f, 0.0f), 0.01f, vec3(1.0f));
  const vec3 p(0.3f, 0.0f, -0.2f);
  const vec3 to_centre = light.position - p;
  const SphereCone cone = sphere_cone(glm::dot(to_centre, to_centre), sqr(light.radius));
  for (const vec2 u : {vec2(0.1f, 0.2f), vec2(0.9f, 0.6f)}) {
    const LightSample s = sample_sphere_light(light, p, u);
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s.pdf, 1.0f / cone.solid_angle());
    EXPECT_GE(glm::dot(s.wi, glm::normalize(to_centre)), cone.cos_max * (1.0f - 1e-6f));
  }
  EXPECT_EQ(sphere_light_pdf(light, p), 1.0f / cone.solid_angle());
}

}  // namespace
}  // namespace bounce
