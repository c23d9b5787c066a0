#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bounce/core/rng.h"
#include "bounce/scene/texture.h"

namespace bounce {
namespace {

// A 5x3 texture whose texels are all different (odd sizes: a wrap off by one shows).
Texture numbered_texture() {
  Texture t;
  t.width = 5;
  t.height = 3;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x)
      t.texels.push_back(vec3(float(x), float(y), float(10 * y + x)));
  return t;
}

// Bilinear with repeat wrapping, spelled out in double precision with a true modulo.
vec3 reference_sample(const Texture& t, vec2 uv) {
  const double x = double(uv.x) * t.width - 0.5, y = double(uv.y) * t.height - 0.5;
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const auto texel = [&](double tx, double ty) {
    const int ix = int(tx - t.width * std::floor(tx / t.width));
    const int iy = int(ty - t.height * std::floor(ty / t.height));
    return t.texels[size_t(iy * t.width + ix)];
  };
  const float fx = float(x - fx0), fy = float(y - fy0);
  const vec3 top = glm::mix(texel(fx0, fy0), texel(fx0 + 1, fy0), fx);
  const vec3 bottom = glm::mix(texel(fx0, fy0 + 1), texel(fx0 + 1, fy0 + 1), fx);
  return glm::mix(top, bottom, fy);
}

TEST(Texture, RepeatWrappingEqualsBilinearWithATrueModulo) {
  const Texture t = numbered_texture();
  Pcg32 rng(7);
  for (int k = 0; k < 4000; ++k) {
    const vec2 uv(6.0f * rng.next_float() - 3.0f, 6.0f * rng.next_float() - 3.0f);
    const vec3 got = t.sample(uv), want = reference_sample(t, uv);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 2e-3f) << uv.x << ", " << uv.y;
  }
  // Texel centres, the image's edges and corners, whole repeats away.
  for (int r = -2; r <= 2; ++r) {
    for (int y = 0; y <= 2 * t.height; ++y) {
      for (int x = 0; x <= 2 * t.width; ++x) {
        const vec2 uv(float(r) + 0.5f * float(x) / float(t.width),
                      float(-r) + 0.5f * float(y) / float(t.height));
        const vec3 got = t.sample(uv), want = reference_sample(t, uv);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 2e-3f) << uv.x << ", " << uv.y;
      }
    }
  }
}

TEST(Texture, CoordinatesAtTheLimitsReadTexelsOfTheImage) {
  const Texture t = numbered_texture();
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float tiny = -std::numeric_limits<float>::denorm_min();
  // A tiny negative coordinate rounds to the end of its repeat: the last column blended with the
  // first, as at u = 0.
  EXPECT_EQ(t.sample(vec2(tiny, 0.5f)), t.sample(vec2(0.0f, 0.5f)));
  for (const float u : {inf, -inf, nan, 1e30f, -1e30f, tiny}) {
    for (const float v : {0.5f, inf, nan, -1e30f}) {
      const vec3 s = t.sample(vec2(u, v));
      // Every result is a blend of texels: within the texels' range, and finite.
      for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(s[c])) << u << ", " << v;
        EXPECT_GE(s[c], 0.0f);
        EXPECT_LE(s[c], 24.0f);
      }
    }
  }
}

}  // namespace
}  // namespace bounce
