// The shared low-resolution estimate (render/lowres_estimate.h) on a hand-made G-buffer with a
// depth discontinuity: pixels whose low-resolution neighbours lie on the other side are
// estimated at full resolution, the others are interpolated, and the counts are exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "bounce/render/lowres_estimate.h"

namespace bounce {
namespace {

constexpr int kSize = 16;
constexpr int kStep = 8;  // columns x < kStep lie on the near plane (z = 1), the rest at z = 3

// The G-buffer planes the low-resolution estimate reads, kSize x kSize.
struct SmallGBuffer {
  std::vector<vec3> position = std::vector<vec3>(kSize * kSize);
  std::vector<vec3> normal = std::vector<vec3>(kSize * kSize);
  std::vector<uint32_t> primitive = std::vector<uint32_t>(kSize * kSize);
  ConstGBufferView view() const {
    ConstGBufferView g;
    g.position = position.data();
    g.normal = normal.data();
    g.primitive = primitive.data();
    g.width = g.height = kSize;
    return g;
  }
};

struct TwoPlanes : SmallGBuffer {
  TwoPlanes() {
    std::fill(normal.begin(), normal.end(), vec3(0, 0, 1));
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const size_t i = size_t(y) * kSize + size_t(x);
        position[i] = vec3(0.1f * float(x), 0.1f * float(y), x < kStep ? 1.0f : 3.0f);
        primitive[i] = x < kStep ? 0 : 1;
      }
  }
};

// Each plane's radiance is a constant, so a blend across the step is visible as a wrong value.
vec3 plane_radiance(int x) {
  return vec3(x < kStep ? 1.0f : 2.0f);
}

TEST(LowResEstimate, EdgesAcrossADepthStepAreEstimatedAtFullResolution) {
  const TwoPlanes planes;
  std::vector<vec3> pixels(kSize * kSize, vec3(-1.0f));
  const ImageView out{pixels.data(), kSize, kSize};
  std::atomic<int> calls{0};
  std::atomic<int>* counter = &calls;
  const auto estimate = [counter](int x, int) {
    counter->fetch_add(1);
    return plane_radiance(x);
  };
  LowResBuffers low;
  StageTimes times;
  // Within a plane the interpolated position is off by at most one pixel's 0.1 (at the clamped
  // borders); across the step by half the depth gap or more.
  const EdgeTest edges{0.99f, 0.3f, false};
  const size_t edge_count = estimate_at_low_res(planes.view(), 2, edges, estimate, low, out, times);

  // Samples at x = 2 lx + 1: pixels 7 and 8 interpolate samples 7 and 9, one on each plane.
  EXPECT_EQ(edge_count, size_t(2 * kSize));
  EXPECT_EQ(calls.load(), (kSize / 2) * (kSize / 2) + 2 * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) ASSERT_EQ(out.at(x, y), plane_radiance(x)) << x << ", " << y;

  // The debug view marks exactly those pixels.
  const EdgeTest shown{0.99f, 0.3f, true};
  estimate_at_low_res(planes.view(), 2, shown, estimate, low, out, times);
  int yellow = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) yellow += out.at(x, y) == vec3(1, 1, 0) ? 1 : 0;
  EXPECT_EQ(yellow, 2 * kSize);
}

TEST(LowResEstimate, WithoutTheEdgeTestTheStepIsBlurred) {
  // The same frame with edges never detected: the pixels beside the step blend both planes,
  // which is what the re-estimate above avoids.
  const TwoPlanes planes;
  std::vector<vec3> pixels(kSize * kSize);
  const ImageView out{pixels.data(), kSize, kSize};
  LowResBuffers low;
  StageTimes times;
  const EdgeTest never{-2.0f, 1e9f, false};
  const size_t edge_count = estimate_at_low_res(
      planes.view(), 2, never, [](int x, int) { return plane_radiance(x); }, low, out, times);
  EXPECT_EQ(edge_count, 0u);
  EXPECT_FLOAT_EQ(out.at(7, 5).x, 1.25f);  // 3/4 of sample 7 (1), 1/4 of sample 9 (2)
  EXPECT_FLOAT_EQ(out.at(8, 5).x, 1.75f);
}

// A plane over columns x < 12 and nothing beyond (a background), but for one pixel at (14, 6)
// whose four samples all see nothing. Radiance grows with x, so a blend that counted the missing
// samples as black would read low.
struct PlaneAndBackground : SmallGBuffer {
  PlaneAndBackground() {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const size_t i = size_t(y) * kSize + size_t(x);
        const bool hit = x < 12 || (x == 14 && y == 6);
        position[i] = hit ? vec3(0.1f * float(x), 0.1f * float(y), 1.0f) : vec3(0.0f);
        normal[i] = hit ? vec3(0, 0, 1) : vec3(0.0f);
        primitive[i] = hit ? 0 : kNoPrimitive;
      }
  }
};

TEST(LowResEstimate, SamplesThatMissAreReestimatedOrBlendedAround) {
  const PlaneAndBackground scene;
  std::vector<vec3> pixels(kSize * kSize, vec3(-1.0f));
  const ImageView out{pixels.data(), kSize, kSize};
  std::atomic<int> calls{0};
  std::atomic<int>* counter = &calls;
  const ConstGBufferView g = scene.view();
  const auto estimate = [counter, g](int x, int y) {
    counter->fetch_add(1);
    return g.hit(g.index(x, y)) ? vec3(1.0f + 0.1f * float(x)) : vec3(0.0f);
  };
  LowResBuffers low;
  StageTimes times;
  // Samples at x = 2 lx + 1: column 11 blends sample 11 (3/4) with sample 13, which missed.
  EdgeTest edges{-1.0f, 1e9f, false, true};
  EXPECT_EQ(estimate_at_low_res(g, 2, edges, estimate, low, out, times), size_t(kSize + 1));
  EXPECT_EQ(calls.load(), 64 + kSize + 1);
  for (int y = 0; y < kSize; ++y) EXPECT_FLOAT_EQ(out.at(11, y).x, 2.1f);  // its own estimate
  // Blended instead: column 11 takes sample 11 alone; only the island, whose samples all
  // missed, is estimated itself.
  edges.misses = false;
  calls = 0;
  EXPECT_EQ(estimate_at_low_res(g, 2, edges, estimate, low, out, times), 1u);
  EXPECT_EQ(calls.load(), 64 + 1);
  for (int y = 0; y < kSize; ++y) EXPECT_FLOAT_EQ(out.at(11, y).x, 2.1f) << y;
  EXPECT_FLOAT_EQ(out.at(14, 6).x, 2.4f);
  // Pixels whose blend took no missing sample are the same either way.
  EXPECT_FLOAT_EQ(out.at(9, 4).x, 0.75f * 1.9f + 0.25f * 2.1f);  // samples 9 and 11
  EXPECT_EQ(out.at(13, 2), vec3(0.0f));                          // no surface
}

TEST(LowResEstimate, FactorOneEstimatesEveryPixel) {
  const TwoPlanes planes;
  std::vector<vec3> pixels(kSize * kSize);
  const ImageView out{pixels.data(), kSize, kSize};
  LowResBuffers low;
  StageTimes times;
  const size_t edge_count = estimate_at_low_res(
      planes.view(), 1, EdgeTest{}, [](int x, int y) { return vec3(float(x), float(y), 0.0f); },
      low, out, times);
  EXPECT_EQ(edge_count, 0u);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) ASSERT_EQ(out.at(x, y), vec3(float(x), float(y), 0.0f));
}

}  // namespace
}  // namespace bounce
