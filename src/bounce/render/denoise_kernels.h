// The denoiser's per-pixel bodies (render/denoiser.h): demodulation, temporal reprojection and
// accumulation, the variance estimate, one a-trous wavelet pass and remodulation. They work on
// structure-of-arrays float planes, so the CPU's row loops (denoiser.cpp) vectorise; a GPU
// launcher calls the same bodies once per pixel.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#if !BOUNCE_DEVICE_CODE
#include <bit>
#endif

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"

// Forced inlining: the a-trous body must be one basic block inside the row loop to vectorise.
#if defined(__CUDACC__)
#define BOUNCE_DENOISE_INLINE __forceinline__
#define BOUNCE_DENOISE_LAMBDA_INLINE
#elif defined(__GNUC__)
#define BOUNCE_DENOISE_INLINE __attribute__((always_inline)) inline
#define BOUNCE_DENOISE_LAMBDA_INLINE __attribute__((always_inline))
#else
#define BOUNCE_DENOISE_INLINE inline
#define BOUNCE_DENOISE_LAMBDA_INLINE
#endif

namespace bounce::denoise {

// An albedo channel at or below this is "black": light is demodulated by 1 there.
inline constexpr float kAlbedoFloor = 1e-3f;
// The local depth slope never counts as less than this fraction of the depth (fronto-parallel
// planes have a zero slope, and rounding alone would otherwise stop the filter).
inline constexpr float kDepthSlopeFloor = 1e-3f;
inline constexpr float kDepthEpsilon = 1e-8f;
inline constexpr float kLuminanceEpsilon = 1e-6f;
// Reprojected history is kept when its accepted bilinear taps weigh at least this much.
inline constexpr float kMinHistoryWeight = 0.01f;
// Below this many frames in a pixel's estimate its variance is estimated spatially.
inline constexpr float kShortHistory = 4.0f;
inline constexpr int kSpatialVarianceRadius = 3;  // 7x7
inline constexpr float kLog2e = 1.44269504f;

template <typename T, bool kConst>
using Ptr = maybe_const_t<T, kConst>*;

// A colour as three float planes.
template <bool kConst>
struct RgbPlanesT {
  Ptr<float, kConst> r = nullptr;
  Ptr<float, kConst> g = nullptr;
  Ptr<float, kConst> b = nullptr;

  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator RgbPlanesT<kTo>() const { return {r, g, b}; }
  BOUNCE_HD vec3 get(size_t i) const { return {r[i], g[i], b[i]}; }
  BOUNCE_HD void set(size_t i, vec3 c) const {
    r[i] = c.x;
    g[i] = c.y;
    b[i] = c.z;
  }
};
using RgbPlanes = RgbPlanesT<false>;
using ConstRgbPlanes = RgbPlanesT<true>;

// This frame's surfaces as planes. Pixels without a surface have depth 0, normal 0 (so every
// edge-stopping weight to them is 0) and object kNoPrimitive.
template <bool kConst>
struct SurfacePlanesT {
  Ptr<float, kConst> depth = nullptr;
  Ptr<float, kConst> nx = nullptr;
  Ptr<float, kConst> ny = nullptr;
  Ptr<float, kConst> nz = nullptr;
  Ptr<uint32_t, kConst> object = nullptr;  // the G-buffer's mesh id

  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator SurfacePlanesT<kTo>() const {
    return {depth, nx, ny, nz, object};
  }
  BOUNCE_HD bool hit(size_t i) const { return object[i] != kNoPrimitive; }
  BOUNCE_HD vec3 normal(size_t i) const { return {nx[i], ny[i], nz[i]}; }
};
using SurfacePlanes = SurfacePlanesT<false>;
using ConstSurfacePlanes = SurfacePlanesT<true>;

// What a pixel keeps for the next frame: demodulated light accumulated over `length` earlier
// frames plus this one, luminance moments, and, at rest, the running average of the
// demodulation factor and the emission (jittered frames see several surfaces per pixel).
template <bool kConst>
struct HistoryT {
  RgbPlanesT<kConst> direct, indirect;
  Ptr<float, kConst> direct_m1 = nullptr;  // mean luminance
  Ptr<float, kConst> direct_m2 = nullptr;  // mean squared luminance
  Ptr<float, kConst> indirect_m1 = nullptr;
  Ptr<float, kConst> indirect_m2 = nullptr;
  RgbPlanesT<kConst> factor, emission;
  Ptr<float, kConst> length = nullptr;  // earlier frames in the estimate (0: none)

  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator HistoryT<kTo>() const {
    return {direct,      indirect, direct_m1, direct_m2, indirect_m1,
            indirect_m2, factor,   emission,  length};
  }
};
using History = HistoryT<false>;
using ConstHistory = HistoryT<true>;

BOUNCE_HD inline float luminance_of(float r, float g, float b) {
  return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}
BOUNCE_HD inline float luminance_of(vec3 c) {
  return luminance_of(c.x, c.y, c.z);
}

// What light is divided by: the albedo, or 1 where a channel is black (nothing to divide).
BOUNCE_HD inline vec3 demodulation_factor(vec3 albedo) {
  return {albedo.x > kAlbedoFloor ? albedo.x : 1.0f, albedo.y > kAlbedoFloor ? albedo.y : 1.0f,
          albedo.z > kAlbedoFloor ? albedo.z : 1.0f};
}

// 2^x for x <= 0, and exactly 0 below -126: the filter's weights. On the CPU a polynomial
// (relative error ~1e-7) that vectorises, with one exponent per tap.
BOUNCE_HD BOUNCE_DENOISE_INLINE float exp2_weight(float x) {
#if BOUNCE_DEVICE_CODE
  return x < -126.0f ? 0.0f : exp2f(x < 0.0f ? x : 0.0f);
#else
  const float c = x < -126.0f ? -126.0f : (x < 0.0f ? x : 0.0f);
  const float whole = std::floor(c);
  const float f = c - whole;
  const float p = 0.99999989f +
                  f * (0.69315475f +
                       f * (0.24013971f + f * (0.05586624f + f * (0.00894283f + f * 0.00189646f))));
  const float scale = std::bit_cast<float>(uint32_t(int32_t(whole) + 127) << 23);
  // Selects between constants only: with trapping maths on, GCC would not hoist arithmetic
  // back out of a branch, and the row loops would not vectorise.
  return p * scale * (x < -126.0f ? 0.0f : 1.0f);
#endif
}

// log2(x) for x in (0, 1] (normal agreement), absolute error ~1e-5.
BOUNCE_HD BOUNCE_DENOISE_INLINE float log2_unit(float x) {
#if BOUNCE_DEVICE_CODE
  return log2f(x);
#else
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const float e = float(int32_t(bits >> 23) - 127);
  const float m = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u) - 1.0f;
  return e +
         m * (1.44268480f +
              m * (-0.72051970f +
                   m * (0.46991988f + m * (-0.30511980f + m * (0.14841024f - m * 0.03538566f)))));
#endif
}

// log2 of the normal edge-stopping weight max(0, n_p . n_q)^sigma_normal; very negative (a zero
// weight) where the normals disagree or a pixel has no surface.
BOUNCE_HD BOUNCE_DENOISE_INLINE float normal_log2_weight(float cos_pq, float sigma_normal) {
  const float c = cos_pq > 1e-6f ? (cos_pq < 1.0f ? cos_pq : 1.0f) : 1e-6f;
  return sigma_normal * log2_unit(c) + (cos_pq > 1e-6f ? 0.0f : -1e4f);
}

// ---- Demodulation ---------------------------------------------------------------------------

struct DemodulatePass {
  ConstGBufferView g;
  const vec3* direct = nullptr;    // direct light with the emission the G-buffer saw
  const vec3* indirect = nullptr;  // null without indirect light
  RgbPlanes out_direct, out_indirect;
  SurfacePlanes out_surface;
  vec2* out_motion = nullptr;  // a copy of the G-buffer's motion, for the debug view
};

// Splits pixel i into demodulated planes and surface planes. Pixels without a surface (background,
// a sphere light seen directly) keep their light as it is: no filter tap reaches them, and the
// remodulation leaves their images untouched.
BOUNCE_HD inline void demodulate_pixel(const DemodulatePass& p, size_t i) {
  p.out_motion[i] = p.g.motion[i];
  if (!p.g.hit(i)) {
    p.out_surface.depth[i] = p.out_surface.nx[i] = p.out_surface.ny[i] = p.out_surface.nz[i] = 0.0f;
    p.out_surface.object[i] = kNoPrimitive;
    p.out_direct.set(i, p.direct[i]);
    if (p.indirect) p.out_indirect.set(i, p.indirect[i]);
    return;
  }
  const vec3 inv = 1.0f / demodulation_factor(p.g.albedo[i]);
  p.out_direct.set(i, (p.direct[i] - p.g.emission[i]) * inv);
  if (p.indirect) p.out_indirect.set(i, p.indirect[i] * inv);
  const vec3 n = p.g.normal[i];
  p.out_surface.depth[i] = p.g.depth[i];
  p.out_surface.nx[i] = n.x;
  p.out_surface.ny[i] = n.y;
  p.out_surface.nz[i] = n.z;
  p.out_surface.object[i] = p.g.mesh[i];
}

// ---- Temporal reprojection and accumulation --------------------------------------------------

struct TemporalSettings {
  bool history = false;    // last frame's history may be used (temporal on, no reset)
  bool reproject = false;  // through the motion with consistency tests; else the same pixel (rest)
  bool clip = false;       // clamp the history to this frame's neighbourhood (world changed)
  bool has_indirect = false;
  float cap_direct = 0.0f;    // history length cap for direct light (infinite at rest)
  float cap_indirect = 0.0f;  // and for indirect light
  float clip_gamma = 1.0f;
  float depth_tolerance = 0.0f;
  float normal_tolerance = 0.0f;
};

struct TemporalPass {
  ConstGBufferView g;                       // this frame's (albedo, emission, motion)
  ConstRgbPlanes raw_direct, raw_indirect;  // this frame, demodulated
  ConstSurfacePlanes surface, prev_surface;
  ConstHistory prev;
  History next;
  int width = 0;
  int height = 0;
  TemporalSettings s;
};

// Last frame's history at one pixel, as a weighted sum of taps.
struct HistorySample {
  float weight = 0.0f;
  vec3 direct{0.0f}, indirect{0.0f};
  float direct_m1 = 0.0f, direct_m2 = 0.0f, indirect_m1 = 0.0f, indirect_m2 = 0.0f;
  float length = 0.0f;

  BOUNCE_HD void add(const ConstHistory& h, size_t q, float w, bool indirect_light) {
    weight += w;
    direct += w * h.direct.get(q);
    direct_m1 += w * h.direct_m1[q];
    direct_m2 += w * h.direct_m2[q];
    if (indirect_light) {
      indirect += w * h.indirect.get(q);
      indirect_m1 += w * h.indirect_m1[q];
      indirect_m2 += w * h.indirect_m2[q];
    }
    length += w * h.length[q];
  }
  BOUNCE_HD void normalize() {
    const float inv = 1.0f / weight;
    direct *= inv;
    indirect *= inv;
    direct_m1 *= inv;
    direct_m2 *= inv;
    indirect_m1 *= inv;
    indirect_m2 *= inv;
    length *= inv;
  }
};

// Whether last frame's pixel q shows the surface this frame's pixel i shows (SVGF's tests).
BOUNCE_HD inline bool consistent(const TemporalPass& p, size_t i, size_t q) {
  if (p.prev_surface.object[q] != p.surface.object[i]) return false;
  const float z = p.surface.depth[i];
  if (std::fabs(p.prev_surface.depth[q] - z) > p.s.depth_tolerance * z) return false;
  return glm::dot(p.prev_surface.normal(q), p.surface.normal(i)) >= p.s.normal_tolerance;
}

// Last frame's history for this frame's pixel (x, y), weight 0 where there is none.
BOUNCE_HD inline HistorySample reproject(const TemporalPass& p, int x, int y, size_t i) {
  HistorySample h;
  if (!p.s.reproject) {
    // At rest the pixel sees the same surface: the same pixel, no filtering, no tests (jittered
    // frames may see another object at an edge, and that is the antialiasing).
    if (p.prev_surface.hit(i)) h.add(p.prev, i, 1.0f, p.s.has_indirect);
    return h;
  }
  // Bilinear taps around where the surface was: pixel centres are at integer + 0.5.
  const vec2 m = p.g.motion[i];
  const float px = float(x) - m.x, py = float(y) - m.y;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  const int x0 = int(fx0), y0 = int(fy0);
  for (int k = 0; k < 4; ++k) {
    const int dx = k & 1, dy = k >> 1;
    const float w = (dx ? fx : 1.0f - fx) * (dy ? fy : 1.0f - fy);
    const int qx = x0 + dx, qy = y0 + dy;
    if (w <= 0.0f || qx < 0 || qy < 0 || qx >= p.width || qy >= p.height) continue;
    const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
    if (consistent(p, i, q)) h.add(p.prev, q, w, p.s.has_indirect);
  }
  return h;
}

// Mean and standard deviation per channel of this frame's demodulated light around (x, y),
// over the 3x3 pixels with a surface.
struct ColorBox {
  vec3 mean{0.0f}, sigma{0.0f};
};
BOUNCE_HD inline ColorBox neighbourhood(const TemporalPass& p, ConstRgbPlanes light, int x, int y) {
  vec3 s1(0.0f), s2(0.0f);
  float n = 0.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if (qx < 0 || qy < 0 || qx >= p.width || qy >= p.height) continue;
      const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
      if (!p.surface.hit(q)) continue;
      const vec3 c = light.get(q);
      s1 += c;
      s2 += c * c;
      n += 1.0f;
    }
  }
  ColorBox box;
  box.mean = s1 / n;
  box.sigma = glm::sqrt(glm::max(s2 / n - box.mean * box.mean, vec3(0.0f)));
  return box;
}

// Clamps a history colour into mean +- gamma sigma and moves its first luminance moment with it
// (keeping the moments' variance).
BOUNCE_HD inline void clip_history(const ColorBox& box, float gamma, vec3& color, float& m1,
                                   float& m2) {
  const vec3 clipped =
      glm::clamp(color, box.mean - gamma * box.sigma, box.mean + gamma * box.sigma);
  const float l = luminance_of(clipped);
  m2 += l * l - m1 * m1;
  m1 = l;
  color = clipped;
}

// Blends this frame's demodulated light at (x, y) into the reprojected history and writes the
// next history. alpha = 1 / (n + 1) with n the (capped) history length: a plain running average
// while n is below the cap.
BOUNCE_HD inline void temporal_pixel(const TemporalPass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  const History& next = p.next;
  const vec3 raw_d = p.raw_direct.get(i);
  const vec3 raw_i = p.s.has_indirect ? p.raw_indirect.get(i) : vec3(0.0f);
  if (!p.surface.hit(i)) {
    next.direct.set(i, raw_d);
    next.direct_m1[i] = next.direct_m2[i] = 0.0f;
    if (p.s.has_indirect) {
      next.indirect.set(i, raw_i);
      next.indirect_m1[i] = next.indirect_m2[i] = 0.0f;
    }
    next.factor.set(i, vec3(1.0f));
    next.emission.set(i, vec3(0.0f));
    next.length[i] = 0.0f;
    return;
  }
  HistorySample h;
  if (p.s.history) h = reproject(p, x, y, i);
  const bool kept = h.weight >= kMinHistoryWeight;
  if (kept) h.normalize();
  if (kept && p.s.clip) {
    clip_history(neighbourhood(p, p.raw_direct, x, y), p.s.clip_gamma, h.direct, h.direct_m1,
                 h.direct_m2);
    if (p.s.has_indirect)
      clip_history(neighbourhood(p, p.raw_indirect, x, y), p.s.clip_gamma, h.indirect,
                   h.indirect_m1, h.indirect_m2);
  }
  const float n = kept ? glm::min(h.length + 1.0f, p.s.cap_direct) : 0.0f;
  const float alpha = 1.0f / (n + 1.0f);
  const float l_d = luminance_of(raw_d);
  next.direct.set(i, h.direct + (raw_d - h.direct) * alpha);
  next.direct_m1[i] = h.direct_m1 + (l_d - h.direct_m1) * alpha;
  next.direct_m2[i] = h.direct_m2 + (l_d * l_d - h.direct_m2) * alpha;
  if (p.s.has_indirect) {
    const float alpha_i = 1.0f / (glm::min(n, p.s.cap_indirect) + 1.0f);
    const float l_i = luminance_of(raw_i);
    next.indirect.set(i, h.indirect + (raw_i - h.indirect) * alpha_i);
    next.indirect_m1[i] = h.indirect_m1 + (l_i - h.indirect_m1) * alpha_i;
    next.indirect_m2[i] = h.indirect_m2 + (l_i * l_i - h.indirect_m2) * alpha_i;
  }
  // What the light is remodulated with: this frame's, or at rest the average of the frames.
  const vec3 factor = demodulation_factor(p.g.albedo[i]);
  const vec3 emission = p.g.emission[i];
  if (kept && !p.s.reproject) {
    const vec3 f0 = p.prev.factor.get(i), e0 = p.prev.emission.get(i);
    next.factor.set(i, f0 + (factor - f0) * alpha);
    next.emission.set(i, e0 + (emission - e0) * alpha);
  } else {
    next.factor.set(i, factor);
    next.emission.set(i, emission);
  }
  next.length[i] = n;
}

// ---- Variance -------------------------------------------------------------------------------

struct VariancePass {
  ConstSurfacePlanes surface;
  ConstHistory history;          // this frame's accumulation
  float* depth_slope = nullptr;  // out: |dz/dx| + |dz/dy|, from the flatter side of each axis
  float* var_direct = nullptr;   // out: luminance variance of the accumulated mean
  float* var_indirect = nullptr;
  int width = 0;
  int height = 0;
  bool has_indirect = false;
  float cap_indirect = 0.0f;
  float sigma_normal = 0.0f;
  float sigma_depth = 0.0f;
};

// The smaller depth difference to the two neighbours along one axis that have a surface.
BOUNCE_HD inline float axis_slope(const ConstSurfacePlanes& s, size_t i, float z, bool has_before,
                                  size_t before, bool has_after, size_t after) {
  float slope = 0.0f;
  bool any = false;
  if (has_before && s.hit(before)) {
    slope = std::fabs(z - s.depth[before]);
    any = true;
  }
  if (has_after && s.hit(after)) {
    const float d = std::fabs(s.depth[after] - z);
    slope = any ? glm::min(slope, d) : d;
  }
  return slope;
}

BOUNCE_HD inline float depth_slope_at(const ConstSurfacePlanes& s, int width, int height, int x,
                                      int y) {
  const size_t i = size_t(y) * size_t(width) + size_t(x);
  const float z = s.depth[i];
  const size_t w = size_t(width);
  return axis_slope(s, i, z, x > 0, i - 1, x + 1 < width, i + 1) +
         axis_slope(s, i, z, y > 0, i - w, y + 1 < height, i + w);
}

// Writes the depth slope and the variance of pixel (x, y)'s accumulated mean: the moments'
// variance over the frames where the history is long enough, else a 7x7 bilateral estimate
// (depth and normal weights) from the neighbours' moments; divided by the frames averaged.
BOUNCE_HD inline void variance_pixel(const VariancePass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  const ConstHistory& h = p.history;
  if (!p.surface.hit(i)) {
    p.depth_slope[i] = 0.0f;
    p.var_direct[i] = 0.0f;
    if (p.has_indirect) p.var_indirect[i] = 0.0f;
    return;
  }
  const float slope = depth_slope_at(p.surface, p.width, p.height, x, y);
  p.depth_slope[i] = slope;
  const float frames = h.length[i] + 1.0f;
  float m1_d = h.direct_m1[i], m2_d = h.direct_m2[i];
  float m1_i = p.has_indirect ? h.indirect_m1[i] : 0.0f;
  float m2_i = p.has_indirect ? h.indirect_m2[i] : 0.0f;
  if (frames < kShortHistory) {
    const float zp = p.surface.depth[i];
    const vec3 np = p.surface.normal(i);
    const float inv_phi =
        kLog2e / (p.sigma_depth * (slope + kDepthSlopeFloor * zp) + kDepthEpsilon);
    float sw = 1.0f;
    constexpr int r = kSpatialVarianceRadius;
    for (int dy = -r; dy <= r; ++dy) {
      const int qy = y + dy;
      if (qy < 0 || qy >= p.height) continue;
      for (int dx = -r; dx <= r; ++dx) {
        const int qx = x + dx;
        if (qx < 0 || qx >= p.width || (dx == 0 && dy == 0)) continue;
        const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
        const float dz = std::fabs(p.surface.depth[q] - zp);
        const float e = normal_log2_weight(glm::dot(np, p.surface.normal(q)), p.sigma_normal) -
                        dz * inv_phi / std::sqrt(float(dx * dx + dy * dy));
        const float w = exp2_weight(e);
        sw += w;
        m1_d += w * h.direct_m1[q];
        m2_d += w * h.direct_m2[q];
        if (p.has_indirect) {
          m1_i += w * h.indirect_m1[q];
          m2_i += w * h.indirect_m2[q];
        }
      }
    }
    m1_d /= sw;
    m2_d /= sw;
    m1_i /= sw;
    m2_i /= sw;
  }
  p.var_direct[i] = glm::max(m2_d - m1_d * m1_d, 0.0f) / frames;
  if (p.has_indirect)
    p.var_indirect[i] =
        glm::max(m2_i - m1_i * m1_i, 0.0f) / (glm::min(frames, p.cap_indirect + 1.0f));
}

// ---- A-trous wavelet pass ---------------------------------------------------------------------

struct AtrousPass {
  ConstSurfacePlanes surface;
  const float* depth_slope = nullptr;
  ConstRgbPlanes in_direct, in_indirect;
  const float* in_var_direct = nullptr;
  const float* in_var_indirect = nullptr;
  RgbPlanes out_direct, out_indirect;
  float* out_var_direct = nullptr;
  float* out_var_indirect = nullptr;
  int width = 0;
  int height = 0;
  int step = 1;  // 2^iteration
  float sigma_luminance = 0.0f;
  float sigma_normal = 0.0f;
  float sigma_depth = 0.0f;
};

// The 1D kernel the 2D one is the outer product of: 3 taps (1/4, 1/2, 1/4) or SVGF's 5-tap
// B3 spline (1/16, 1/4, 3/8, 1/4, 1/16).
template <int kRadius>
BOUNCE_HD constexpr float atrous_kernel(int d) {
  if constexpr (kRadius == 1) {
    return d == 0 ? 0.5f : 0.25f;
  } else {
    static_assert(kRadius == 2, "a-trous kernels are 3x3 or 5x5");
    return d == 0 ? 0.375f : (d == 1 || d == -1) ? 0.25f : 0.0625f;
  }
}

template <typename F, int... k>
BOUNCE_HD BOUNCE_DENOISE_INLINE void unrolled_impl(F& f, std::integer_sequence<int, k...>) {
  (f(std::integral_constant<int, k>{}), ...);
}
// Calls f(integral_constant<int, k>) for k in [0, count): loops the compiler sees unrolled.
template <int kCount, typename F>
BOUNCE_HD BOUNCE_DENOISE_INLINE void unrolled(F&& f) {
  unrolled_impl(f, std::make_integer_sequence<int, kCount>{});
}

// Running sums of one light's taps.
struct AtrousSum {
  float w = 0.0f, r = 0.0f, g = 0.0f, b = 0.0f, v = 0.0f;

  BOUNCE_HD BOUNCE_DENOISE_INLINE void add(float weight, ConstRgbPlanes c, const float* var,
                                           size_t q) {
    w += weight;
    r += weight * c.r[q];
    g += weight * c.g[q];
    b += weight * c.b[q];
    v += weight * weight * var[q];
  }
  BOUNCE_HD BOUNCE_DENOISE_INLINE void store(RgbPlanes c, float* var, size_t i) const {
    const float inv = 1.0f / w;
    c.r[i] = r * inv;
    c.g[i] = g * inv;
    c.b[i] = b * inv;
    var[i] = v * inv * inv;
  }
};

// The rows one a-trous pass at row y reads: for each tap row (dy = -kRadius..kRadius times the
// step) and each prefilter row (dy = -1..1), the index of its first pixel and a mask that is 0
// outside the image (the row is then replaced by row y, so reads stay valid). The CPU computes
// them once per row, so the pixel loop has no row tests left.
template <int kRadius>
struct AtrousRows {
  size_t tap[2 * kRadius + 1];
  float tap_mask[2 * kRadius + 1];
  size_t near[3];
  float near_mask[3];
};

template <int kRadius>
BOUNCE_HD inline AtrousRows<kRadius> atrous_rows(const AtrousPass& p, int y) {
  AtrousRows<kRadius> rows;
  const size_t w = size_t(p.width);
  for (int k = 0; k < 2 * kRadius + 1; ++k) {
    const int qy = y + (k - kRadius) * p.step;
    const bool inside = qy >= 0 && qy < p.height;
    rows.tap[k] = size_t(inside ? qy : y) * w;
    rows.tap_mask[k] = inside ? 1.0f : 0.0f;
  }
  for (int k = 0; k < 3; ++k) {
    const int qy = y + k - 1;
    const bool inside = qy >= 0 && qy < p.height;
    rows.near[k] = size_t(inside ? qy : y) * w;
    rows.near_mask[k] = inside ? 1.0f : 0.0f;
  }
  return rows;
}

// One a-trous pass at pixel (x, y) of the row `rows` describes: taps (dx, dy) * step, each
// weighted by the kernel and by edge-stopping functions of depth (relative to the depth slope
// times the tap distance), normal (cosine to the power sigma_normal) and luminance (in units of
// sigma_luminance times the standard deviation from the centre's variance, prefiltered over 3x3),
// one exponential per light and tap. The variance is filtered along with the squared weights.
// Columns outside the image are masked only when kCheckColumns (the CPU's interior loop leaves
// it off, and is then branch-free: it vectorises).
template <int kRadius, bool kIndirect, bool kCheckColumns>
BOUNCE_HD BOUNCE_DENOISE_INLINE void atrous_pixel(const AtrousPass& p,
                                                  const AtrousRows<kRadius>& rows, int x) {
  const int w = p.width;
  const size_t c = rows.tap[kRadius] + size_t(x);
  const float zp = p.surface.depth[c];
  const float nxp = p.surface.nx[c], nyp = p.surface.ny[c], nzp = p.surface.nz[c];

  // The centre's variance, prefiltered over the 3x3 pixels with a surface.
  float vd = 0.0f, vi = 0.0f, vw = 0.0f;
  unrolled<9>([&](auto k) BOUNCE_DENOISE_LAMBDA_INLINE {
    constexpr int dx = decltype(k)::value % 3 - 1, dy = decltype(k)::value / 3 - 1;
    constexpr float hk = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
    float mask = rows.near_mask[dy + 1];
    int qx = x + dx;
    if constexpr (kCheckColumns) {
      const bool inside = (qx >= 0) & (qx < w);
      mask = inside ? mask : 0.0f;
      qx = inside ? qx : x;
    }
    const size_t q = rows.near[dy + 1] + size_t(qx);
    const float wk = mask * (p.surface.depth[q] > 0.0f ? hk : 0.0f);
    vw += wk;
    vd += wk * p.in_var_direct[q];
    if constexpr (kIndirect) vi += wk * p.in_var_indirect[q];
  });
  const float inv_vw = 1.0f / (vw > 0.0f ? vw : 1.0f);
  const float inv_phi_d = kLog2e / (p.sigma_luminance * std::sqrt(vd * inv_vw) + kLuminanceEpsilon);
  const float inv_phi_i =
      kIndirect ? kLog2e / (p.sigma_luminance * std::sqrt(vi * inv_vw) + kLuminanceEpsilon) : 0.0f;
  const float inv_phi_z =
      kLog2e /
      (p.sigma_depth * float(p.step) * (p.depth_slope[c] + kDepthSlopeFloor * zp) + kDepthEpsilon);

  const float lp_d = luminance_of(p.in_direct.r[c], p.in_direct.g[c], p.in_direct.b[c]);
  const float lp_i =
      kIndirect ? luminance_of(p.in_indirect.r[c], p.in_indirect.g[c], p.in_indirect.b[c]) : 0.0f;
  constexpr float kCentre = atrous_kernel<kRadius>(0) * atrous_kernel<kRadius>(0);
  AtrousSum sd, si;
  sd.add(kCentre, p.in_direct, p.in_var_direct, c);
  if constexpr (kIndirect) si.add(kCentre, p.in_indirect, p.in_var_indirect, c);

  constexpr int kSide = 2 * kRadius + 1;
  unrolled<kSide * kSide>([&](auto k) BOUNCE_DENOISE_LAMBDA_INLINE {
    constexpr int dx = decltype(k)::value % kSide - kRadius;
    constexpr int dy = decltype(k)::value / kSide - kRadius;
    if constexpr (dx != 0 || dy != 0) {
      constexpr float hk = atrous_kernel<kRadius>(dx) * atrous_kernel<kRadius>(dy);
      const float inv_distance = 1.0f / std::sqrt(float(dx * dx + dy * dy));
      float kernel = hk * rows.tap_mask[dy + kRadius];
      int qx = x + dx * p.step;
      if constexpr (kCheckColumns) {
        const bool inside = (qx >= 0) & (qx < w);
        kernel = inside ? kernel : 0.0f;
        qx = inside ? qx : x;
      }
      const size_t q = rows.tap[dy + kRadius] + size_t(qx);
      const float cos_pq = nxp * p.surface.nx[q] + nyp * p.surface.ny[q] + nzp * p.surface.nz[q];
      const float geometry = normal_log2_weight(cos_pq, p.sigma_normal) -
                             std::fabs(p.surface.depth[q] - zp) * (inv_phi_z * inv_distance);
      const float l_d = luminance_of(p.in_direct.r[q], p.in_direct.g[q], p.in_direct.b[q]);
      sd.add(kernel * exp2_weight(geometry - std::fabs(l_d - lp_d) * inv_phi_d), p.in_direct,
             p.in_var_direct, q);
      if constexpr (kIndirect) {
        const float l_i = luminance_of(p.in_indirect.r[q], p.in_indirect.g[q], p.in_indirect.b[q]);
        si.add(kernel * exp2_weight(geometry - std::fabs(l_i - lp_i) * inv_phi_i), p.in_indirect,
               p.in_var_indirect, q);
      }
    }
  });
  sd.store(p.out_direct, p.out_var_direct, c);
  if constexpr (kIndirect) si.store(p.out_indirect, p.out_var_indirect, c);
}

// ---- Remodulation ---------------------------------------------------------------------------

struct RemodulatePass {
  ConstSurfacePlanes surface;
  ConstHistory history;  // the factor and emission to remodulate with
  ConstRgbPlanes direct, indirect;
  vec3* out_direct = nullptr;
  vec3* out_indirect = nullptr;  // null without indirect light
};

// Multiplies the filtered light back by its albedo and adds the emission; pixels without a
// surface keep what the techniques wrote.
BOUNCE_HD inline void remodulate_pixel(const RemodulatePass& p, size_t i) {
  if (!p.surface.hit(i)) return;
  const vec3 f = p.history.factor.get(i);
  p.out_direct[i] = p.direct.get(i) * f + p.history.emission.get(i);
  if (p.out_indirect) p.out_indirect[i] = p.indirect.get(i) * f;
}

}  // namespace bounce::denoise
