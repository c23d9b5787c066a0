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
// frames plus this one, and its luminance moments, as three 4-vectors, so that blending four of
// them (bilinear reprojection) is a few vector operations.
struct HistoryTexel {
  vec4 direct{0.0f};    // rgb, mean luminance
  vec4 indirect{0.0f};  // rgb, mean luminance
  vec4 extra{0.0f};     // mean squared luminance of direct and of indirect light, length, unused

  BOUNCE_HD float length() const { return extra.z; }
  BOUNCE_HD void add(float w, const HistoryTexel& t) {
    direct += w * t.direct;
    indirect += w * t.indirect;
    extra += w * t.extra;
  }
};

// The demodulation factor and the emission averaged over the frames at rest, so that jittered
// frames, which see several surfaces in an edge pixel, converge to the average of what they saw.
struct RestAverage {
  vec3 factor;
  vec3 emission;
};

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

// 2^x for x <= 0, and exactly 0 below -126: the filter's weights. On the CPU a cubic (relative
// error 1e-4, plenty for a weight) that vectorises.
BOUNCE_HD BOUNCE_DENOISE_INLINE float exp2_weight(float x) {
#if BOUNCE_DEVICE_CODE
  return x < -126.0f ? 0.0f : exp2f(x < 0.0f ? x : 0.0f);
#else
  const float c = x < -126.0f ? -126.0f : (x < 0.0f ? x : 0.0f);
  const float whole = std::floor(c);
  const float f = c - whole;
  const float p = 0.99989297f + f * (0.69645728f + f * (0.22433866f + f * 0.07920405f));
  const float scale = std::bit_cast<float>(uint32_t(int32_t(whole) + 127) << 23);
  // Selects between constants only, so no arithmetic is left in a branch.
  return p * scale * (x < -126.0f ? 0.0f : 1.0f);
#endif
}

// log2 of the normal edge-stopping weight max(0, cos)^sigma_normal, from the series
// ln(cos) = -(t + t^2/2 + t^3/3 + ...) with t = 1 - cos: accurate (1e-3) wherever the weight is
// not ~0, three multiply-adds instead of a logarithm; a zero weight where cos <= 0 (opposite
// normals, or a pixel without a surface, whose normal is 0).
BOUNCE_HD BOUNCE_DENOISE_INLINE float normal_log2_weight(float cos_pq, float sigma_normal) {
  const float t = 1.0f - cos_pq;
  return -(sigma_normal * kLog2e) * t * (1.0f + t * (0.5f + t * (1.0f / 3.0f))) +
         (cos_pq > 0.0f ? 0.0f : -1e4f);
}

// ---- Temporal reprojection and accumulation --------------------------------------------------

struct TemporalSettings {
  bool history = false;    // last frame's history may be used (temporal on, no reset)
  bool reproject = false;  // through the motion with consistency tests; else the same pixel (rest)
  bool clip = false;       // clamp the history to this frame's neighbourhood (world changed)
  bool rest_continues = false;  // at rest, and the last frame was too: RestAverage continues
  bool has_indirect = false;
  float cap_direct = 0.0f;    // history length cap for direct light (infinite at rest)
  float cap_indirect = 0.0f;  // and for indirect light
  float clip_gamma = 1.0f;
  float depth_tolerance = 0.0f;
  float normal_tolerance = 0.0f;
};

struct TemporalPass {
  ConstGBufferView g;              // this frame's
  const vec3* direct = nullptr;    // direct light with the emission the G-buffer saw
  const vec3* indirect = nullptr;  // null without indirect light
  ConstSurfacePlanes prev_surface;
  const HistoryTexel* prev = nullptr;
  // Out: the next history, this frame's surfaces, the accumulated light (the filter's input),
  // the luminance variance of its mean from the moments over the frames, the history length.
  HistoryTexel* next = nullptr;
  SurfacePlanes surface;
  RgbPlanes light_direct, light_indirect;
  float* var_direct = nullptr;
  float* var_indirect = nullptr;
  float* length = nullptr;
  RestAverage* rest = nullptr;  // updated in place at rest
  int width = 0;
  int height = 0;
  TemporalSettings s;
};

// This frame's light at pixel i (which has a surface), demodulated; emission set apart.
BOUNCE_HD inline void demodulated(const TemporalPass& p, size_t i, vec3& direct, vec3& indirect) {
  const vec3 inv = 1.0f / demodulation_factor(p.g.albedo[i]);
  direct = (p.direct[i] - p.g.emission[i]) * inv;
  indirect = p.indirect ? p.indirect[i] * inv : vec3(0.0f);
}

// Whether last frame's pixel q shows the surface this frame's pixel i shows (SVGF's tests).
BOUNCE_HD inline bool consistent(const TemporalPass& p, size_t i, size_t q) {
  if (p.prev_surface.object[q] != p.g.mesh[i]) return false;
  const float z = p.g.depth[i];
  if (std::fabs(p.prev_surface.depth[q] - z) > p.s.depth_tolerance * z) return false;
  return glm::dot(p.prev_surface.normal(q), p.g.normal[i]) >= p.s.normal_tolerance;
}

// Last frame's history for this frame's pixel (x, y): the normalised sum of the taps kept.
struct Reprojected {
  HistoryTexel h;
  bool kept = false;
};
BOUNCE_HD inline Reprojected reproject(const TemporalPass& p, int x, int y, size_t i) {
  Reprojected r;
  if (!p.s.reproject) {
    // At rest the pixel sees the same surface: the same pixel, no filtering, no tests (jittered
    // frames may see another object at an edge, and that is the antialiasing).
    r.kept = p.prev_surface.hit(i);
    if (r.kept) r.h = p.prev[i];
    return r;
  }
  // Bilinear taps around where the surface was: pixel centres are at integer + 0.5.
  const vec2 m = p.g.motion[i];
  const float px = float(x) - m.x, py = float(y) - m.y;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  const int x0 = int(fx0), y0 = int(fy0);
  float weight = 0.0f;
  for (int k = 0; k < 4; ++k) {
    const int dx = k & 1, dy = k >> 1;
    const float w = (dx ? fx : 1.0f - fx) * (dy ? fy : 1.0f - fy);
    const int qx = x0 + dx, qy = y0 + dy;
    if (w <= 0.0f || qx < 0 || qy < 0 || qx >= p.width || qy >= p.height) continue;
    const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
    if (!consistent(p, i, q)) continue;
    weight += w;
    r.h.add(w, p.prev[q]);
  }
  r.kept = weight >= kMinHistoryWeight;
  if (!r.kept) return Reprojected{};
  const float inv = 1.0f / weight;
  r.h.direct *= inv;
  r.h.indirect *= inv;
  r.h.extra *= inv;
  return r;
}

// Mean and standard deviation per channel of this frame's demodulated light around (x, y), over
// the 3x3 pixels with a surface.
struct ColorBox {
  vec3 mean{0.0f}, sigma{0.0f};
};
struct ColorBoxes {
  ColorBox direct, indirect;
};
BOUNCE_HD inline ColorBoxes neighbourhood(const TemporalPass& p, int x, int y) {
  vec3 d1(0.0f), d2(0.0f), i1(0.0f), i2(0.0f);
  float n = 0.0f;
  for (int qy = glm::max(y - 1, 0); qy <= glm::min(y + 1, p.height - 1); ++qy) {
    for (int qx = glm::max(x - 1, 0); qx <= glm::min(x + 1, p.width - 1); ++qx) {
      const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
      if (!p.g.hit(q)) continue;
      vec3 d, ind;
      demodulated(p, q, d, ind);
      d1 += d;
      d2 += d * d;
      i1 += ind;
      i2 += ind * ind;
      n += 1.0f;
    }
  }
  auto box = [n](vec3 s1, vec3 s2) {
    ColorBox b;
    b.mean = s1 / n;
    b.sigma = glm::sqrt(glm::max(s2 / n - b.mean * b.mean, vec3(0.0f)));
    return b;
  };
  return {box(d1, d2), box(i1, i2)};
}

// Clamps a history colour (rgb, mean luminance) into mean +- gamma sigma and moves its mean
// luminance with it, keeping the moments' variance (m2 is the mean squared luminance).
BOUNCE_HD inline void clip_history(const ColorBox& box, float gamma, vec4& color, float& m2) {
  const vec3 clipped =
      glm::clamp(vec3(color), box.mean - gamma * box.sigma, box.mean + gamma * box.sigma);
  const float l = luminance_of(clipped);
  m2 += l * l - color.w * color.w;
  color = vec4(clipped, l);
}

// Blends this frame's demodulated light at (x, y) into the reprojected history and writes the
// next history and the filter's inputs. alpha = 1 / (n + 1) with n the (capped) history length:
// a plain running average while n is below the cap. Returns whether the pixel's history is too
// short for its own variance (the spatial estimate then stands in).
BOUNCE_HD inline bool temporal_pixel(const TemporalPass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  if (!p.g.hit(i)) {
    // No surface: the light passes through (the remodulation leaves it alone), no history.
    p.next[i] = HistoryTexel{};
    p.surface.depth[i] = p.surface.nx[i] = p.surface.ny[i] = p.surface.nz[i] = 0.0f;
    p.surface.object[i] = kNoPrimitive;
    p.light_direct.set(i, p.direct[i]);
    if (p.indirect) p.light_indirect.set(i, p.indirect[i]);
    p.var_direct[i] = p.var_indirect[i] = 0.0f;
    p.length[i] = 0.0f;
    return false;
  }
  const vec3 normal = p.g.normal[i];
  p.surface.depth[i] = p.g.depth[i];
  p.surface.nx[i] = normal.x;
  p.surface.ny[i] = normal.y;
  p.surface.nz[i] = normal.z;
  p.surface.object[i] = p.g.mesh[i];

  vec3 raw_d, raw_i;
  demodulated(p, i, raw_d, raw_i);
  Reprojected r;
  if (p.s.history) r = reproject(p, x, y, i);
  HistoryTexel& h = r.h;
  if (r.kept && p.s.clip) {
    const ColorBoxes boxes = neighbourhood(p, x, y);
    clip_history(boxes.direct, p.s.clip_gamma, h.direct, h.extra.x);
    if (p.indirect) clip_history(boxes.indirect, p.s.clip_gamma, h.indirect, h.extra.y);
  }
  const float n = r.kept ? glm::min(h.length() + 1.0f, p.s.cap_direct) : 0.0f;
  const float alpha = 1.0f / (n + 1.0f);
  const float alpha_i = 1.0f / (glm::min(n, p.s.cap_indirect) + 1.0f);
  // This frame as a texel, blended in: colour and mean luminance, mean squared luminance.
  const float l_d = luminance_of(raw_d), l_i = luminance_of(raw_i);
  HistoryTexel next;
  next.direct = h.direct + (vec4(raw_d, l_d) - h.direct) * alpha;
  next.indirect = h.indirect + (vec4(raw_i, l_i) - h.indirect) * alpha_i;
  next.extra = vec4(h.extra.x + (l_d * l_d - h.extra.x) * alpha,
                    h.extra.y + (l_i * l_i - h.extra.y) * alpha_i, n, 0.0f);
  p.next[i] = next;
  p.light_direct.set(i, vec3(next.direct));
  if (p.indirect) p.light_indirect.set(i, vec3(next.indirect));
  // The variance of the mean of the frames (the spatial estimate replaces it where n is small).
  p.var_direct[i] = glm::max(next.extra.x - next.direct.w * next.direct.w, 0.0f) / (n + 1.0f);
  p.var_indirect[i] = glm::max(next.extra.y - next.indirect.w * next.indirect.w, 0.0f) /
                      (glm::min(n, p.s.cap_indirect) + 1.0f);
  p.length[i] = n;
  if (p.rest) {
    // The rest average continues where this pixel's history does, else it starts here.
    RestAverage& rest = p.rest[i];
    const vec3 factor = demodulation_factor(p.g.albedo[i]), emission = p.g.emission[i];
    if (r.kept && p.s.rest_continues) {
      rest.factor += (factor - rest.factor) * alpha;
      rest.emission += (emission - rest.emission) * alpha;
    } else {
      rest.factor = factor;
      rest.emission = emission;
    }
  }
  return n + 1.0f < kShortHistory;
}

// ---- Depth slope ------------------------------------------------------------------------------

// |dz/dx| + |dz/dy| at pixel x of the row starting at `row`, each from the flatter side (so a
// depth edge does not count); `up` and `down` are the neighbouring rows' starts (the row itself
// outside the image). Sides without a surface (depth 0) or outside the image do not count.
template <bool kCheckColumns>
BOUNCE_HD BOUNCE_DENOISE_INLINE float depth_slope_pixel(const float* depth, int width, size_t row,
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
  const HistoryTexel* history = nullptr;  // this frame's accumulation, with its moments
  const float* depth = nullptr;           // > 0 where there is a surface
  float* sums[5] = {};  // out: moments summed along rows (direct m1, m2, indirect m1, m2), count
  int width = 0;
};

// Row sums at pixel x of the row starting at index `row`.
BOUNCE_HD inline void box_row_pixel(const BoxPass& p, size_t row, int x) {
  float s[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int qx = glm::max(x - kVarianceBox, 0); qx <= glm::min(x + kVarianceBox, p.width - 1);
       ++qx) {
    const size_t q = row + size_t(qx);
    if (!(p.depth[q] > 0.0f)) continue;
    const HistoryTexel& t = p.history[q];
    s[0] += t.direct.w;
    s[1] += t.extra.x;
    s[2] += t.indirect.w;
    s[3] += t.extra.y;
    s[4] += 1.0f;
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

// Where pixel (x, y)'s history is short, replaces its variance by the box estimate divided by the
// frames averaged.
BOUNCE_HD inline void spatial_variance_pixel(const VariancePass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  const float frames = p.length[i] + 1.0f;
  if (!(frames < kShortHistory) || !(p.depth[i] > 0.0f)) return;
  float s[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int qy = glm::max(y - kVarianceBox, 0); qy <= glm::min(y + kVarianceBox, p.height - 1);
       ++qy) {
    const size_t q = size_t(qy) * size_t(p.width) + size_t(x);
    for (int c = 0; c < 5; ++c) s[c] += p.sums[c][q];
  }
  const float inv = 1.0f / s[4];
  const float m1_d = s[0] * inv, m2_d = s[1] * inv, m1_i = s[2] * inv, m2_i = s[3] * inv;
  p.var_direct[i] = glm::max(m2_d - m1_d * m1_d, 0.0f) / frames;
  p.var_indirect[i] = glm::max(m2_i - m1_i * m1_i, 0.0f) / glm::min(frames, p.cap_indirect + 1.0f);
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

  template <bool kVariance>
  BOUNCE_HD BOUNCE_DENOISE_INLINE void add(float weight, ConstRgbPlanes c, const float* var,
                                           size_t q) {
    w += weight;
    r += weight * c.r[q];
    g += weight * c.g[q];
    b += weight * c.b[q];
    if constexpr (kVariance) v += weight * weight * var[q];
  }
  template <bool kVariance>
  BOUNCE_HD BOUNCE_DENOISE_INLINE void store(RgbPlanes c, float* var, size_t i) const {
    const float inv = 1.0f / w;
    c.r[i] = r * inv;
    c.g[i] = g * inv;
    c.b[i] = b * inv;
    if constexpr (kVariance) var[i] = v * inv * inv;
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
// it off, and is then branch-free: it vectorises). Without kVariance (the last pass) the
// variance is not filtered.
template <int kRadius, bool kIndirect, bool kCheckColumns, bool kVariance = true>
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
  sd.add<kVariance>(kCentre, p.in_direct, p.in_var_direct, c);
  if constexpr (kIndirect) si.add<kVariance>(kCentre, p.in_indirect, p.in_var_indirect, c);

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
      sd.add<kVariance>(kernel * exp2_weight(geometry - std::fabs(l_d - lp_d) * inv_phi_d),
                        p.in_direct, p.in_var_direct, q);
      if constexpr (kIndirect) {
        const float l_i = luminance_of(p.in_indirect.r[q], p.in_indirect.g[q], p.in_indirect.b[q]);
        si.add<kVariance>(kernel * exp2_weight(geometry - std::fabs(l_i - lp_i) * inv_phi_i),
                          p.in_indirect, p.in_var_indirect, q);
      }
    }
  });
  sd.store<kVariance>(p.out_direct, p.out_var_direct, c);
  if constexpr (kIndirect) si.store<kVariance>(p.out_indirect, p.out_var_indirect, c);
}

// ---- Remodulation ---------------------------------------------------------------------------

struct RemodulatePass {
  ConstGBufferView g;
  const RestAverage* rest = nullptr;  // at rest: remodulate with the averages, else this frame's
  ConstRgbPlanes direct, indirect;    // filtered
  vec3* out_direct = nullptr;
  vec3* out_indirect = nullptr;  // null without indirect light
};

// Multiplies the filtered light back by its albedo and adds the emission; pixels without a
// surface keep what the techniques wrote.
BOUNCE_HD inline void remodulate_pixel(const RemodulatePass& p, size_t i) {
  if (!p.g.hit(i)) return;
  const vec3 f = p.rest ? p.rest[i].factor : demodulation_factor(p.g.albedo[i]);
  const vec3 e = p.rest ? p.rest[i].emission : p.g.emission[i];
  p.out_direct[i] = p.direct.get(i) * f + e;
  if (p.out_indirect) p.out_indirect[i] = p.indirect.get(i) * f;
}

}  // namespace bounce::denoise
