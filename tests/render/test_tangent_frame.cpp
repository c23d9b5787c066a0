// Tangent frames from texture coordinates: orthonormal, and on a plane with an affine uv mapping
// they are the analytic frame: the tangent along dP/du, the bitangent along -dP/dv (glTF: up the
// image), mirrored mappings included.
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/core/rng.h"
#include "bounce/render/tangent_frame.h"

namespace bounce {
namespace {

void expect_near(vec3 a, vec3 b, float tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(TangentFrame, OrthonormalAndAnalyticOnAPlane) {
  Pcg32 rng(7);
  auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
  for (int trial = 0; trial < 200; ++trial) {
    // A plane through `origin` spanned by orthonormal a (where u grows) and b (where v grows),
    // with scales su, sv (negative: mirrored), and a triangle on it.
    const vec3 n = glm::normalize(vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
    const vec3 helper = std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
    const vec3 a = glm::normalize(glm::cross(helper, n));
    const vec3 b = glm::cross(n, a) * (trial % 2 ? -1.0f : 1.0f);
    const float su = uniform(0.5f, 3.0f) * (trial % 3 ? 1.0f : -1.0f), sv = uniform(0.5f, 3.0f);
    const vec3 origin(uniform(-5, 5), uniform(-5, 5), uniform(-5, 5));
    const vec2 shift(uniform(-2, 2), uniform(-2, 2));
    auto point = [&](vec2 uv) {
      return origin + a * ((uv.x - shift.x) / su) + b * ((uv.y - shift.y) / sv);
    };
    const vec2 uv0(uniform(0, 1), uniform(0, 1)), uv1(uniform(0, 1), uniform(0, 1)),
        uv2(uniform(0, 1), uniform(0, 1));
    const float area = (uv1.x - uv0.x) * (uv2.y - uv0.y) - (uv2.x - uv0.x) * (uv1.y - uv0.y);
    if (std::abs(area) < 0.05f) continue;
    TangentFrame f;
    ASSERT_TRUE(tangent_frame(point(uv0), point(uv1), point(uv2), uv0, uv1, uv2, n, f));
    EXPECT_NEAR(glm::length(f.tangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(f.bitangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.tangent, f.bitangent), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.tangent, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(f.bitangent, n), 0.0f, 1e-5f);
    // dP/du = a / su, dP/dv = b / sv.
    expect_near(f.tangent, su > 0 ? a : -a, 1e-4f);
    expect_near(f.bitangent, -b, 1e-4f);
  }
}

TEST(TangentFrame, DegenerateUvsGiveNoFrame) {
  TangentFrame f;
  EXPECT_FALSE(tangent_frame(vec3(0), vec3(1, 0, 0), vec3(0, 1, 0), vec2(0.5f), vec2(0.5f),
                             vec2(0.5f), vec3(0, 0, 1), f));
  EXPECT_FALSE(tangent_frame(vec3(0), vec3(1, 0, 0), vec3(0, 1, 0), vec2(0), vec2(1, 1), vec2(2, 2),
                             vec3(0, 0, 1), f));
}

}  // namespace
}  // namespace bounce
