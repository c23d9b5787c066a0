// What the denoiser's a-trous filter needs besides the light (render/denoise_kernels.h): the local
// depth slope its depth weights are relative to, and the spatial variance estimate that stands in
// where a pixel's history is short.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "bounce/render/denoise_kernels.h"

namespace bounce::denoise {

// ---- Depth slope ------------------------------------------------------------------------------

// |dz/dx| + |dz/dy| at pixel x of the row starting at `row`, each from the flatter side (so a
// depth edge does not count); `up` and `down` are the neighbouring rows' starts (the row itself
// outside the image). Sides without a surface (depth 0) or outside the image do not count.
template <bool kCheckColumns>
BOUNCE_HD BOUNCE_LANE_INLINE float depth_slope_pixel(const float* depth, int width, size_t row,
                                                     size_t up, size_t down, int x) {
  constexpr float kNone = 1e30f;
  const size_t i = row + size_t(x);
  const float z = depth[i];
  auto side = [z](float q) { return q > 0.0f ? std::fabs(q - z) : kNone; };
  float left = kNone, right = kNone;
  if constexpr (kCheckColumns) {
    if (x > 0) left = side(depth[i - 1]);
    if (x + 1 < width) right = side(depth[i + 1]);
  } else {
    left = side(depth[i - 1]);
    right = side(depth[i + 1]);
  }
  const float sx = glm::min(left, right),
              sy = glm::min(side(depth[up + size_t(x)]), side(depth[down + size_t(x)]));
  return z > 0.0f ? (sx < kNone ? sx : 0.0f) + (sy < kNone ? sy : 0.0f) : 0.0f;
}

// ---- Spatial variance ---------------------------------------------------------------------------
// Where a pixel's history is short, its variance comes from its neighbourhood: the moments summed
// over a 7x7 box of pixels with a surface (a separable sum: a row pass, then a column pass), only
// around rows that hold such pixels. Unlike SVGF's 7x7 bilateral estimate it ignores geometry;
// the a-trous weights still stop at geometric edges, and the box costs a few additions per pixel
// whatever the number of short pixels (all of them after a reset).

inline constexpr int kVarianceBox = 3;  // radius: 7x7

struct BoxPass {
  ConstHistoryPlanes history;    // this frame's accumulation, with its moments
  const float* depth = nullptr;  // > 0 where there is a surface
  float* sums[5] = {};  // out: moments summed along rows (direct m1, m2, indirect m1, m2), count
  int width = 0;
};

// What one pixel adds to the box sums: its moments (direct m1, m2, indirect m1, m2) and a count
// of 1, or nothing where it has no surface.
BOUNCE_HD BOUNCE_LANE_INLINE void box_moments(const HistoryTexel& t, float depth, float m[5]) {
  const float on = depth > 0.0f ? 1.0f : 0.0f;
  m[0] = on * luminance_of(vec3(t.direct));
  m[1] = on * t.direct.w;
  m[2] = on * luminance_of(vec3(t.indirect));
  m[3] = on * t.indirect.w;
  m[4] = on;
}

// Row sums at pixel x of the row starting at index `row`.
BOUNCE_HD inline void box_row_pixel(const BoxPass& p, size_t row, int x) {
  float s[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int qx = glm::max(x - kVarianceBox, 0); qx <= glm::min(x + kVarianceBox, p.width - 1);
       ++qx) {
    const size_t q = row + size_t(qx);
    float m[5];
    box_moments(p.history.get(q), p.depth[q], m);
    for (int k = 0; k < 5; ++k) s[k] += m[k];
  }
  for (int k = 0; k < 5; ++k) p.sums[k][row + size_t(x)] = s[k];
}

struct VariancePass {
  const float* depth = nullptr;   // > 0 where there is a surface
  const float* length = nullptr;  // history length
  const float* sums[5] = {};      // BoxPass's output
  float* var_direct = nullptr;    // in/out: luminance variance of the accumulated mean
  float* var_indirect = nullptr;
  int width = 0;
  int height = 0;
  float cap_indirect = 0.0f;
};

// The luminance variances of the moments of a box (box_moments' sums `s`): direct, indirect.
BOUNCE_HD BOUNCE_LANE_INLINE void box_moment_variances(const float s[5], float& var_d,
                                                       float& var_i) {
  const float inv = 1.0f / (s[4] > 0.0f ? s[4] : 1.0f);
  const float m1_d = s[0] * inv, m2_d = s[1] * inv, m1_i = s[2] * inv, m2_i = s[3] * inv;
  var_d = glm::max(m2_d - m1_d * m1_d, 0.0f);
  var_i = glm::max(m2_i - m1_i * m1_i, 0.0f);
}

// The frames a pixel's estimate averages, of direct and of indirect light (the latter capped for
// a technique that accumulates indirect light itself), from its history length.
BOUNCE_HD BOUNCE_LANE_INLINE void averaged_frames(float length, float cap_indirect, float& frames_d,
                                                  float& frames_i) {
  frames_d = length + 1.0f;
  frames_i = glm::min(frames_d, cap_indirect + 1.0f);
}

// The box estimate at pixel i from its box sums `s`: where the history is short (and there is a
// surface), the variance of the box's moments divided by the frames averaged replaces the
// pixel's own; elsewhere the pixel keeps it. Branch-free, so a row loop vectorises.
BOUNCE_HD BOUNCE_LANE_INLINE void box_variance(const VariancePass& p, size_t i, const float s[5]) {
  float frames, frames_i;
  averaged_frames(p.length[i], p.cap_indirect, frames, frames_i);
  const bool short_history = (frames < kShortHistory) & (p.depth[i] > 0.0f);
  float box_d, box_i;
  box_moment_variances(s, box_d, box_i);
  const float var_d = box_d / frames;
  const float var_i = box_i / frames_i;
  p.var_direct[i] = short_history ? var_d : p.var_direct[i];
  p.var_indirect[i] = short_history ? var_i : p.var_indirect[i];
}

// Pixel (x, y): the column sum of BoxPass's row sums, then box_variance.
BOUNCE_HD inline void spatial_variance_pixel(const VariancePass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  float s[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int qy = glm::max(y - kVarianceBox, 0); qy <= glm::min(y + kVarianceBox, p.height - 1);
       ++qy) {
    const size_t q = size_t(qy) * size_t(p.width) + size_t(x);
    for (int c = 0; c < 5; ++c) s[c] += p.sums[c][q];
  }
  box_variance(p, i, s);
}

// ---- The spatial variance at half resolution ---------------------------------------------------
// While every pixel's history is short (the first frames after a reset) and every light is
// filtered at half resolution, the full-resolution estimate above would only be averaged over
// 2x2 blocks by the downsample. Instead the downsample (denoise_half.h) sums each block's moments
// and the box runs over half-resolution texels: a quarter of the pixels, and the history is read
// once. The box is kHalfVarianceBox texels in radius, (4r + 2) pixels across.

inline constexpr int kHalfVarianceBox = 2;

struct HalfVariancePass {
  const float* moments[5] = {};  // the blocks' moment sums (box_moments' order)
  // In: each texel's scale from the downsample (the sum over its pixels on its surface of
  // 1 / frames, over their count squared; 0 without a surface). Out: the variance of the
  // texel's mean. var[1] is null without indirect light.
  float* var[2] = {};
  int width = 0;
  int height = 0;
};

// Texel h from its box's moment sums `s`.
BOUNCE_HD BOUNCE_LANE_INLINE void half_box_variance(const HalfVariancePass& p, size_t h,
                                                    const float s[5]) {
  float var_d, var_i;
  box_moment_variances(s, var_d, var_i);
  p.var[0][h] *= var_d;
  if (p.var[1]) p.var[1][h] *= var_i;
}

// Texel (x, y), summing its box directly (a launcher with one thread per texel; the CPU sums the
// box separably).
BOUNCE_HD inline void half_variance_pixel(const HalfVariancePass& p, int x, int y) {
  constexpr int r = kHalfVarianceBox;
  float s[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int qy = glm::max(y - r, 0); qy <= glm::min(y + r, p.height - 1); ++qy)
    for (int qx = glm::max(x - r, 0); qx <= glm::min(x + r, p.width - 1); ++qx) {
      const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
      for (int k = 0; k < 5; ++k) s[k] += p.moments[k][q];
    }
  half_box_variance(p, size_t(y) * size_t(p.width) + size_t(x), s);
}

}  // namespace bounce::denoise
