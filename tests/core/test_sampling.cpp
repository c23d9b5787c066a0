#include <gtest/gtest.h>

#include "bounce/core/qmc.h"
#include "bounce/core/sampling.h"

namespace bounce {
namespace {

// Integrates a pdf over the sphere of directions by a midpoint rule in (cos theta, phi); with
// n = 2000 the cones' edges below fall on cell boundaries, so piecewise-constant pdfs are exact.
template <typename Pdf>
double integrate_over_sphere(Pdf pdf, int n = 2000) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double z = -1.0 + 2.0 * (i + 0.5) / n;
      const double phi = 2.0 * kPi * (j + 0.5) / n;
      const double r = std::sqrt(1.0 - z * z);
      sum += pdf(vec3(r * std::cos(phi), r * std::sin(phi), z));
    }
  return sum * (2.0 / n) * (2.0 * kPi / n);
}

TEST(Sampling, PdfsIntegrateToOne) {
  EXPECT_NEAR(integrate_over_sphere([](vec3) { return uniform_sphere_pdf(); }), 1.0, 1e-4);
  EXPECT_NEAR(integrate_over_sphere([](vec3 w) { return cosine_hemisphere_pdf(w.z); }), 1.0, 1e-4);
  for (float cos_max : {0.0f, 0.5f, 0.9f}) {
    const double integral = integrate_over_sphere(
        [&](vec3 w) { return w.z >= cos_max ? uniform_cone_pdf(cos_max) : 0.0f; });
    EXPECT_NEAR(integral, 1.0, 1e-5) << cos_max;
  }
}

// The sample warps produce the distributions their pdfs claim: the mean of g(w) / pdf(w) over
// samples estimates the integral of g, checked for g = cos^2 over the hemisphere (= 2 pi / 3).
TEST(Sampling, WarpsMatchTheirPdfs) {
  const uint32_t n = 1 << 16;
  double cosine_est = 0.0, sphere_est = 0.0, cone_est = 0.0;
  const float cos_max = 0.6f;
  for (uint32_t i = 0; i < n; ++i) {
    const vec2 u = sobol2(i);
    const vec3 c = sample_cosine_hemisphere(u);
    EXPECT_NEAR(glm::length(c), 1.0f, 1e-5f);
    cosine_est += c.z * c.z / cosine_hemisphere_pdf(c.z);
    const vec3 s = sample_uniform_sphere(u);
    sphere_est += (s.z > 0.0f ? s.z * s.z : 0.0f) / uniform_sphere_pdf();
    const vec3 k = sample_uniform_cone(u, cos_max);
    ASSERT_GE(k.z, cos_max - 1e-6f);
    cone_est += k.z / uniform_cone_pdf(cos_max);
  }
  EXPECT_NEAR(cosine_est / n, 2.0 * kPi / 3.0, 1e-3);
  EXPECT_NEAR(sphere_est / n, 2.0 * kPi / 3.0, 1e-2);
  // Integral of cos over the cone: pi (1 - cos_max^2).
  EXPECT_NEAR(cone_est / n, kPi * (1.0 - cos_max * cos_max), 1e-3);
}

TEST(Sampling, TriangleAndDiskAreUniform) {
  const uint32_t n = 1 << 14;
  vec2 mean_tri(0.0f), mean_disk(0.0f);
  int inside_half = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const vec2 b = sample_uniform_triangle(sobol2(i));
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    mean_tri += b;
    const vec2 d = sample_concentric_disk(sobol2(i));
    ASSERT_LE(glm::length(d), 1.0f + 1e-6f);
    mean_disk += d;
    inside_half += glm::length(d) < std::sqrt(0.5f);
  }
  // A uniform triangle's barycentric centroid is (1/3, 1/3); half a disk's area lies within
  // radius sqrt(1/2).
  EXPECT_NEAR(mean_tri.x / n, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(mean_tri.y / n, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(mean_disk.x / n, 0.0, 1e-3);
  EXPECT_NEAR(double(inside_half) / n, 0.5, 5e-3);
}

TEST(Sampling, BasisIsOrthonormalForAnyNormal) {
  for (vec3 n : {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), glm::normalize(vec3(1, -2, 3)),
                 glm::normalize(vec3(-1e-4f, 1e-4f, -1.0f))}) {
    const Basis f = Basis::from_normal(n);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.b, f.n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-5f);
    const vec3 v(0.3f, -0.4f, 0.5f);
    const vec3 back = f.to_world(f.to_local(v));
    EXPECT_NEAR(glm::length(back - v), 0.0f, 1e-5f);
  }
}

}  // namespace
}  // namespace bounce
