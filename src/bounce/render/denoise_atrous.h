// The denoiser's edge-avoiding a-trous wavelet filter, per pixel (render/denoise_kernels.h).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "bounce/render/denoise_kernels.h"

namespace bounce::denoise {

// The local depth slope never counts as less than this fraction of the depth (fronto-parallel
// planes have a zero slope, and rounding alone would otherwise stop the filter).
inline constexpr float kDepthSlopeFloor = 1e-3f;
inline constexpr float kDepthEpsilon = 1e-8f;
inline constexpr float kLuminanceEpsilon = 1e-6f;

// One pass weighs each tap (dx, dy) * step by the kernel and by edge-stopping functions of depth
// (relative to the depth slope times the tap distance), normal (cosine to the power
// sigma_normal) and luminance (in units of sigma_luminance times the standard deviation from the
// centre's variance, prefiltered over 3x3): w = 2^(geometry - luminance), one exponential per
// light and tap. The variance is filtered along with the squared weights.
//
// A light whose sigma is 0 stops at no luminance edge: its taps weigh by geometry alone, and it
// needs no variance (indirect light by default, DenoiseSettings::sigma_luminance_indirect).
//
// It is split in two parts: the geometric exponent of every tap (the same for direct and
// indirect light), then one part per light that reads it. On the CPU the first writes a row of
// exponents that the second reads, which keeps each row loop's live values in registers; a GPU
// pixel calls both with a local array (atrous_pixel).

// One light's planes for a pass.
struct AtrousLight {
  ConstRgbPlanes in;
  const float* in_var = nullptr;
  RgbPlanes out;
  float* out_var = nullptr;
};

struct AtrousPass {
  ConstSurfacePlanes surface;
  const float* depth_slope = nullptr;
  AtrousLight direct, indirect;
  int width = 0;
  int height = 0;
  int step = 1;  // 2^iteration
  float sigma_luminance = 0.0f;
  float sigma_luminance_indirect = 0.0f;
  float sigma_normal = 0.0f;
  float sigma_depth = 0.0f;
};

// The 1D kernel the 2D one is the outer product of: 3 taps (1/4, 1/2, 1/4) or SVGF's 5-tap
// B3 spline (1/16, 1/4, 3/8, 1/4, 1/16). 3x3 is what the Denoiser runs: measured on
// bench_denoiser, n 5x5 passes filter about as well as n + 1 3x3 passes at three times the cost
// per pass.
template <int kRadius>
BOUNCE_HD constexpr float atrous_kernel(int d) {
  if constexpr (kRadius == 1) {
    return d == 0 ? 0.5f : 0.25f;
  } else {
    static_assert(kRadius == 2, "a-trous kernels are 3x3 or 5x5");
    return d == 0 ? 0.375f : (d == 1 || d == -1) ? 0.25f : 0.0625f;
  }
}
// Taps but the centre.
template <int kRadius>
inline constexpr int kAtrousTaps = (2 * kRadius + 1) * (2 * kRadius + 1) - 1;

// Tap k's offset in kernel units (k skips the centre).
template <int kRadius, int k>
struct AtrousTap {
  static constexpr int kSide = 2 * kRadius + 1;
  static constexpr int kIndex = k < kAtrousTaps<kRadius> / 2 ? k : k + 1;
  static constexpr int dx = kIndex % kSide - kRadius;
  static constexpr int dy = kIndex / kSide - kRadius;
};

// The rows one a-trous pass at row y reads: for each tap row (dy = -kRadius..kRadius times the
// step) and each prefilter row (dy = -1..1), the index of its first pixel and whether it is
// inside the image (if not it is replaced by row y, so reads stay valid, and masked). The CPU
// computes them once per row, so the pixel loops have no row tests left.
template <int kRadius>
struct AtrousRows {
  size_t tap[2 * kRadius + 1];
  float tap_mask[2 * kRadius + 1];  // 0 inside, very negative (a zero weight) outside
  size_t near[3];
  float near_mask[3];  // 1 inside, 0 outside
};

template <int kRadius>
BOUNCE_HD inline AtrousRows<kRadius> atrous_rows(const AtrousPass& p, int y) {
  AtrousRows<kRadius> rows;
  const size_t w = size_t(p.width);
  for (int k = 0; k < 2 * kRadius + 1; ++k) {
    const int qy = y + (k - kRadius) * p.step;
    const bool inside = qy >= 0 && qy < p.height;
    rows.tap[k] = size_t(inside ? qy : y) * w;
    rows.tap_mask[k] = inside ? 0.0f : -1e4f;
  }
  for (int k = 0; k < 3; ++k) {
    const int qy = y + k - 1;
    const bool inside = qy >= 0 && qy < p.height;
    rows.near[k] = size_t(inside ? qy : y) * w;
    rows.near_mask[k] = inside ? 1.0f : 0.0f;
  }
  return rows;
}

// How a pass treats tap columns outside the image: none (the interior of a row), masked (weight
// 0; the read lands in the neighbouring row or in the padding the CPU's planes carry, so loads
// stay contiguous and the border loops vectorise too), or clamped to the centre and masked (any
// planes: a GPU pixel). Tap indices are signed: a masked tap left of the first row is a negative
// offset into that padding, which an unsigned index would reach only by wrapping around.
enum class Columns { kInside, kMasked, kClamped };

// Tap column x + offset; `mask` becomes `outside` where the column is outside the image.
template <Columns kColumns>
BOUNCE_HD BOUNCE_LANE_INLINE int tap_column(int x, int offset, int width, float& mask,
                                            float outside) {
  int qx = x + offset;
  if constexpr (kColumns != Columns::kInside) {
    const bool inside = (qx >= 0) & (qx < width);
    mask = inside ? mask : outside;
    if constexpr (kColumns == Columns::kClamped) qx = inside ? qx : x;
  }
  return qx;
}

// What atrous_geometry writes per pixel: the geometric exponent of each tap, then the
// luminance scale of each light.
template <int kRadius>
inline constexpr int kAtrousGeometry = kAtrousTaps<kRadius> + 2;

// At pixel x: the geometric exponent of every tap (log2 of kernel weight times normal weight
// times depth weight), to geometry[k * stride] for tap k, and each light's luminance scale
// log2(e) / (sigma_luminance * standard deviation + epsilon), its variance prefiltered over the
// 3x3 pixels with a surface, to geometry[(taps + light) * stride] (light 0 direct, 1 indirect),
// for the lights that stop at luminance edges (kLuminance).
template <int kRadius, bool kIndirect, Columns kColumns, bool kLuminanceDirect = true,
          bool kLuminanceIndirect = true>
BOUNCE_HD BOUNCE_LANE_INLINE void atrous_geometry(const AtrousPass& p,
                                                  const AtrousRows<kRadius>& rows, int x,
                                                  float* geometry, size_t stride) {
  const size_t c = rows.tap[kRadius] + size_t(x);
  const float zp = p.surface.depth[c];
  const float nxp = p.surface.nx[c], nyp = p.surface.ny[c], nzp = p.surface.nz[c];
  const float inv_phi_z =
      kLog2e /
      (p.sigma_depth * float(p.step) * (p.depth_slope[c] + kDepthSlopeFloor * zp) + kDepthEpsilon);
  unrolled<kAtrousTaps<kRadius>>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    using Tap = AtrousTap<kRadius, decltype(k)::value>;
    constexpr float kernel = atrous_kernel<kRadius>(Tap::dx) * atrous_kernel<kRadius>(Tap::dy);
    const float log2_kernel = std::log2(kernel);
    const float inv_distance = 1.0f / std::sqrt(float(Tap::dx * Tap::dx + Tap::dy * Tap::dy));
    float mask = rows.tap_mask[Tap::dy + kRadius];
    const int qx = tap_column<kColumns>(x, Tap::dx * p.step, p.width, mask, -1e4f);
    const ptrdiff_t q = ptrdiff_t(rows.tap[Tap::dy + kRadius]) + qx;
    const float cos_pq = nxp * p.surface.nx[q] + nyp * p.surface.ny[q] + nzp * p.surface.nz[q];
    geometry[size_t(decltype(k)::value) * stride] =
        log2_kernel + mask + normal_log2_weight(cos_pq, p.sigma_normal) -
        std::fabs(p.surface.depth[q] - zp) * (inv_phi_z * inv_distance);
  });
  constexpr bool kScaleIndirect = kIndirect && kLuminanceIndirect;
  if constexpr (kLuminanceDirect || kScaleIndirect) {
    float vd = 0.0f, vi = 0.0f, vw = 0.0f;
    unrolled<9>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
      constexpr int dx = decltype(k)::value % 3 - 1, dy = decltype(k)::value / 3 - 1;
      constexpr float hk = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
      float mask = rows.near_mask[dy + 1];
      const int qx = tap_column<kColumns>(x, dx, p.width, mask, 0.0f);
      const ptrdiff_t q = ptrdiff_t(rows.near[dy + 1]) + qx;
      const float wk = mask * (p.surface.depth[q] > 0.0f ? hk : 0.0f);
      vw += wk;
      if constexpr (kLuminanceDirect) vd += wk * p.direct.in_var[q];
      if constexpr (kScaleIndirect) vi += wk * p.indirect.in_var[q];
    });
    const float inv_vw = 1.0f / (vw > 0.0f ? vw : 1.0f);
    constexpr size_t kScales = size_t(kAtrousTaps<kRadius>);
    if constexpr (kLuminanceDirect)
      geometry[kScales * stride] =
          kLog2e / (p.sigma_luminance * std::sqrt(vd * inv_vw) + kLuminanceEpsilon);
    if constexpr (kScaleIndirect)
      geometry[(kScales + 1) * stride] =
          kLog2e / (p.sigma_luminance_indirect * std::sqrt(vi * inv_vw) + kLuminanceEpsilon);
  }
}

// One light's pass at pixel x (light 0 direct, 1 indirect), with what atrous_geometry wrote.
// Without kVariance (the last pass, or no kLuminance) the variance is not filtered.
template <int kRadius, Columns kColumns, bool kVariance, bool kLuminance = true>
BOUNCE_HD BOUNCE_LANE_INLINE void atrous_light(const AtrousPass& p, int light_index,
                                               const AtrousRows<kRadius>& rows, int x,
                                               const float* geometry, size_t stride) {
  static_assert(kLuminance || !kVariance, "a light without luminance stops has no variance");
  const AtrousLight& light = light_index ? p.indirect : p.direct;
  const size_t c = rows.tap[kRadius] + size_t(x);
  float inv_phi = 0.0f, lp = 0.0f;
  if constexpr (kLuminance) {
    inv_phi = geometry[size_t(kAtrousTaps<kRadius> + light_index) * stride];
    lp = luminance_of(light.in.r[c], light.in.g[c], light.in.b[c]);
  }
  constexpr float kCentre = atrous_kernel<kRadius>(0) * atrous_kernel<kRadius>(0);
  float sw = kCentre, sr = kCentre * light.in.r[c], sg = kCentre * light.in.g[c],
        sb = kCentre * light.in.b[c], sv = 0.0f;
  if constexpr (kVariance) sv = kCentre * kCentre * light.in_var[c];
  unrolled<kAtrousTaps<kRadius>>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    using Tap = AtrousTap<kRadius, decltype(k)::value>;
    float unused = 0.0f;
    const int qx = tap_column<kColumns>(x, Tap::dx * p.step, p.width, unused, 0.0f);
    const ptrdiff_t q = ptrdiff_t(rows.tap[Tap::dy + kRadius]) + qx;
    const float r = light.in.r[q], g = light.in.g[q], b = light.in.b[q];
    float exponent = geometry[size_t(decltype(k)::value) * stride];
    if constexpr (kLuminance) exponent -= std::fabs(luminance_of(r, g, b) - lp) * inv_phi;
    const float w = exp2_weight(exponent);
    sw += w;
    sr += w * r;
    sg += w * g;
    sb += w * b;
    if constexpr (kVariance) sv += w * w * light.in_var[q];
  });
  const float inv = 1.0f / sw;
  light.out.r[c] = sr * inv;
  light.out.g[c] = sg * inv;
  light.out.b[c] = sb * inv;
  if constexpr (kVariance) light.out_var[c] = sv * inv * inv;
}

// The whole pass at pixel (x, y), for a launcher that runs one thread per pixel. kVariance
// applies to the lights with kLuminance.
template <int kRadius, bool kIndirect, bool kVariance, bool kLuminanceDirect = true,
          bool kLuminanceIndirect = true>
BOUNCE_HD inline void atrous_pixel(const AtrousPass& p, int x, int y) {
  const AtrousRows<kRadius> rows = atrous_rows<kRadius>(p, y);
  float geometry[kAtrousGeometry<kRadius>];
  constexpr Columns kClamped = Columns::kClamped;
  atrous_geometry<kRadius, kIndirect, kClamped, kLuminanceDirect, kLuminanceIndirect>(p, rows, x,
                                                                                      geometry, 1);
  atrous_light<kRadius, kClamped, kVariance && kLuminanceDirect, kLuminanceDirect>(p, 0, rows, x,
                                                                                   geometry, 1);
  if constexpr (kIndirect)
    atrous_light<kRadius, kClamped, kVariance && kLuminanceIndirect, kLuminanceIndirect>(
        p, 1, rows, x, geometry, 1);
}

// Runs `launch.template operator()<kIndirect, kVariance, kLuminanceDirect,
// kLuminanceIndirect>()`, the backend's pass with those switches, for a pass over the direct
// slot (`both`: and the indirect slot) that filters variance where asked (`variance`), the
// lights' luminance stops following their sigmas. (In a pass over both slots, direct light
// stops at luminance edges: its sigma is positive.)
template <typename Launch>
void dispatch_atrous(const AtrousPass& pass, bool both, bool variance, const Launch& launch) {
  const bool luminance = pass.sigma_luminance > 0.0f;
  if (!both) {
    if (!luminance) return launch.template operator()<false, false, false, true>();
    return variance ? launch.template operator()<false, true, true, true>()
                    : launch.template operator()<false, false, true, true>();
  }
  if (pass.sigma_luminance_indirect > 0.0f)
    return variance ? launch.template operator()<true, true, true, true>()
                    : launch.template operator()<true, false, true, true>();
  return variance ? launch.template operator()<true, true, true, false>()
                  : launch.template operator()<true, false, true, false>();
}

}  // namespace bounce::denoise
