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

// What a pixel keeps for the next frame besides its history length (a plane of its own): the
// demodulated light accumulated over the earlier frames and this one, and its mean squared
// luminance (the mean luminance is the luminance of the mean), as two 4-vectors, so that blending
// four of them (bilinear reprojection) is a few vector operations.
struct HistoryTexel {
  vec4 direct{0.0f};    // rgb, mean squared luminance
  vec4 indirect{0.0f};  // rgb, mean squared luminance

  BOUNCE_HD void add(float w, const HistoryTexel& t) {
    direct += w * t.direct;
    indirect += w * t.indirect;
  }
};

// The demodulation factor and the emission averaged over the frames at rest, so that jittered
// frames, which see several surfaces in an edge pixel, converge to the average of what they saw.
template <bool kConst>
struct RestPlanesT {
  RgbPlanesT<kConst> factor, emission;

  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator RestPlanesT<kTo>() const {
    return {factor, emission};
  }
};
using RestPlanes = RestPlanesT<false>;
using ConstRestPlanes = RestPlanesT<true>;

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

// c ? a : b as bit operations: no branch for the compiler to thread on, so a row loop full of
// them stays one basic block and vectorises.
BOUNCE_HD BOUNCE_DENOISE_INLINE uint32_t pick(bool c, uint32_t a, uint32_t b) {
  const uint32_t m = 0u - uint32_t(c);
  return (a & m) | (b & ~m);
}
BOUNCE_HD BOUNCE_DENOISE_INLINE float pick(bool c, float a, float b) {
#if BOUNCE_DEVICE_CODE
  return c ? a : b;
#else
  return std::bit_cast<float>(pick(c, std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b)));
#endif
}
BOUNCE_HD BOUNCE_DENOISE_INLINE vec3 pick(bool c, vec3 a, vec3 b) {
  return {pick(c, a.x, b.x), pick(c, a.y, b.y), pick(c, a.z, b.z)};
}
BOUNCE_HD BOUNCE_DENOISE_INLINE vec4 pick(bool c, vec4 a, vec4 b) {
  return {pick(c, a.x, b.x), pick(c, a.y, b.y), pick(c, a.z, b.z), pick(c, a.w, b.w)};
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
  bool rest_continues = false;  // at rest after a reset or rest: the rest averages continue
  float cap_direct = 0.0f;      // history length cap for direct light (infinite at rest)
  float cap_indirect = 0.0f;    // and for indirect light
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
  const float* prev_length = nullptr;
  // Out: the next history, this frame's surfaces, the accumulated light (the filter's input),
  // the luminance variance of its mean from the moments over the frames, the history length.
  HistoryTexel* next = nullptr;
  SurfacePlanes surface;
  RgbPlanes light_direct, light_indirect;
  float* var_direct = nullptr;
  float* var_indirect = nullptr;
  float* length = nullptr;
  RestPlanes rest;  // updated in place at rest and after a reset
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

// Last frame's history for this frame's pixel (x, y): the normalised sum of the taps kept.
struct Reprojected {
  HistoryTexel h;
  float length = 0.0f;
  bool kept = false;
};
BOUNCE_HD inline Reprojected reproject(const TemporalPass& p, int x, int y, size_t i) {
  Reprojected r;
  if (!p.s.reproject) {
    // At rest the pixel sees the same surface: the same pixel, no filtering, no tests (jittered
    // frames may see another object at an edge, and that is the antialiasing).
    r.kept = p.prev_surface.hit(i);
    if (r.kept) {
      r.h = p.prev[i];
      r.length = p.prev_length[i];
    }
    return r;
  }
  // Bilinear taps around where the surface was: pixel centres are at integer + 0.5. A tap is kept
  // where last frame's pixel shows this surface (SVGF's tests: the same object, depth within
  // depth_tolerance relative, normals within normal_tolerance). The four taps are read
  // branch-free (taps outside the image read this pixel with weight 0).
  const vec2 m = p.g.motion[i];
  const float px = float(x) - m.x, py = float(y) - m.y;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  const int x0 = int(glm::clamp(fx0, -2.0f, float(p.width))),
            y0 = int(glm::clamp(fy0, -2.0f, float(p.height)));
  const uint32_t object = p.g.mesh[i];
  const float z = p.g.depth[i], dz_max = p.s.depth_tolerance * z;
  const vec3 normal = p.g.normal[i];
  float weight = 0.0f;
  for (int k = 0; k < 4; ++k) {
    const int dx = k & 1, dy = k >> 1;
    const int qx = x0 + dx, qy = y0 + dy;
    const bool inside = (qx >= 0) & (qy >= 0) & (qx < p.width) & (qy < p.height);
    const size_t q = inside ? size_t(qy) * size_t(p.width) + size_t(qx) : i;
    const bool same = (p.prev_surface.object[q] == object) &
                      (std::fabs(p.prev_surface.depth[q] - z) <= dz_max) &
                      (glm::dot(p.prev_surface.normal(q), normal) >= p.s.normal_tolerance);
    const float w = (inside & same) ? (dx ? fx : 1.0f - fx) * (dy ? fy : 1.0f - fy) : 0.0f;
    weight += w;
    r.h.add(w, p.prev[q]);
    r.length += w * p.prev_length[q];
  }
  r.kept = weight >= kMinHistoryWeight;
  if (!r.kept) return Reprojected{};
  const float inv = 1.0f / weight;
  r.h.direct *= inv;
  r.h.indirect *= inv;
  r.length *= inv;
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

// Clamps a history colour (rgb, mean squared luminance) into mean +- gamma sigma, keeping the
// moments' variance.
BOUNCE_HD inline void clip_history(const ColorBox& box, float gamma, vec4& color) {
  const vec3 clipped =
      glm::clamp(vec3(color), box.mean - gamma * box.sigma, box.mean + gamma * box.sigma);
  const float l0 = luminance_of(vec3(color)), l = luminance_of(clipped);
  color = vec4(clipped, color.w + l * l - l0 * l0);
}

// The first half of the temporal pass at pixel (x, y): last frame's history where it is kept,
// clipped to this frame's neighbourhood when the world changed.
BOUNCE_HD inline Reprojected temporal_history(const TemporalPass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  if (!p.s.history || !p.g.hit(i)) return Reprojected{};
  Reprojected r = reproject(p, x, y, i);
  if (r.kept && p.s.clip) {
    const ColorBoxes boxes = neighbourhood(p, x, y);
    clip_history(boxes.direct, p.s.clip_gamma, r.h.direct);
    if (p.indirect) clip_history(boxes.indirect, p.s.clip_gamma, r.h.indirect);
  }
  return r;
}

// A row of temporal_history's results as planes, where the CPU's first half leaves them for the
// second, whose loop then vectorises.
struct ReprojectedRow {
  float* v[10] = {};  // direct rgb and mean squared luminance, the same of indirect, length, kept

  BOUNCE_HD void store(int x, const Reprojected& r) const {
    for (int c = 0; c < 4; ++c) {
      v[c][x] = r.h.direct[c];
      v[4 + c][x] = r.h.indirect[c];
    }
    v[8][x] = r.length;
    v[9][x] = r.kept ? 1.0f : 0.0f;
  }
};

// ReprojectedRow's entry x, read through plain pointers (the vectoriser's need).
BOUNCE_HD BOUNCE_DENOISE_INLINE Reprojected load_reprojected(const float* const* v, int x) {
  Reprojected r;
  r.h.direct = vec4(v[0][x], v[1][x], v[2][x], v[3][x]);
  r.h.indirect = vec4(v[4][x], v[5][x], v[6][x], v[7][x]);
  r.length = v[8][x];
  r.kept = v[9][x] != 0.0f;
  return r;
}

// The second half at pixel i: blends this frame's demodulated light into the history `r` and
// writes the next history and the filter's inputs. alpha = 1 / (n + 1) with n the (capped)
// history length: a plain running average while n is below the cap. Pixels without a surface
// pass their light through, with no history. Branch-free, so the CPU's row loop vectorises;
// kIndirect and kRest (update the rest averages) are the pass's switches. Returns whether the
// pixel's history is too short for its own variance (the spatial estimate then stands in).
template <bool kIndirect, bool kRest>
BOUNCE_HD BOUNCE_DENOISE_INLINE bool temporal_blend(const TemporalPass& p, size_t i,
                                                    const Reprojected& r) {
  const bool hit = p.g.hit(i);
  const vec3 normal = p.g.normal[i];
  const float depth = p.g.depth[i];
  const uint32_t mesh = p.g.mesh[i];
  p.surface.depth[i] = pick(hit, depth, 0.0f);
  p.surface.nx[i] = pick(hit, normal.x, 0.0f);
  p.surface.ny[i] = pick(hit, normal.y, 0.0f);
  p.surface.nz[i] = pick(hit, normal.z, 0.0f);
  p.surface.object[i] = pick(hit, mesh, kNoPrimitive);

  const vec3 factor = demodulation_factor(p.g.albedo[i]), emission = p.g.emission[i];
  const vec3 inv = 1.0f / factor;
  const vec3 in_d = p.direct[i];
  const vec3 in_i = kIndirect ? p.indirect[i] : vec3(0.0f);
  const vec3 raw_d = (in_d - emission) * inv, raw_i = in_i * inv;
  const bool kept = hit & r.kept;
  const float n = pick(kept, glm::min(r.length + 1.0f, p.s.cap_direct), 0.0f);
  const float alpha = 1.0f / (n + 1.0f);
  const float alpha_i = 1.0f / (glm::min(n, p.s.cap_indirect) + 1.0f);
  // This frame as a texel, blended in: colour, squared luminance.
  const float l_d = luminance_of(raw_d), l_i = luminance_of(raw_i);
  const vec4 h_d = pick(kept, r.h.direct, vec4(0.0f)), h_i = pick(kept, r.h.indirect, vec4(0.0f));
  const vec4 next_d = h_d + (vec4(raw_d, l_d * l_d) - h_d) * alpha;
  const vec4 next_i = h_i + (vec4(raw_i, l_i * l_i) - h_i) * alpha_i;
  p.next[i].direct = pick(hit, next_d, vec4(0.0f));
  p.next[i].indirect = pick(hit, next_i, vec4(0.0f));
  p.light_direct.set(i, pick(hit, vec3(next_d), in_d));
  if constexpr (kIndirect) p.light_indirect.set(i, pick(hit, vec3(next_i), in_i));
  // The variance of the mean of the frames (the spatial estimate replaces it where n is small).
  const float m1_d = luminance_of(vec3(next_d)), m1_i = luminance_of(vec3(next_i));
  p.var_direct[i] = pick(hit, glm::max(next_d.w - m1_d * m1_d, 0.0f) * alpha, 0.0f);
  p.var_indirect[i] = pick(hit, glm::max(next_i.w - m1_i * m1_i, 0.0f) * alpha_i, 0.0f);
  p.length[i] = n;
  if constexpr (kRest) {
    // The rest average continues where this pixel's history does, else it starts here.
    const bool continues = kept & p.s.rest_continues;
    const vec3 f0 = p.rest.factor.get(i), e0 = p.rest.emission.get(i);
    p.rest.factor.set(i, pick(continues, f0 + (factor - f0) * alpha, factor));
    p.rest.emission.set(i, pick(continues, e0 + (emission - e0) * alpha, emission));
  }
  return hit & (n + 1.0f < kShortHistory);
}

// The whole temporal pass at pixel (x, y), for a launcher that runs one thread per pixel.
template <bool kIndirect, bool kRest>
BOUNCE_HD inline bool temporal_pixel(const TemporalPass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  return temporal_blend<kIndirect, kRest>(p, i, temporal_history(p, x, y));
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
    s[0] += luminance_of(vec3(t.direct));
    s[1] += t.direct.w;
    s[2] += luminance_of(vec3(t.indirect));
    s[3] += t.indirect.w;
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
// One pass weighs each tap (dx, dy) * step by the kernel and by edge-stopping functions of depth
// (relative to the depth slope times the tap distance), normal (cosine to the power
// sigma_normal) and luminance (in units of sigma_luminance times the standard deviation from the
// centre's variance, prefiltered over 3x3): w = 2^(geometry - luminance), one exponential per
// light and tap. The variance is filtered along with the squared weights.
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

template <typename F, int... k>
BOUNCE_HD BOUNCE_DENOISE_INLINE void unrolled_impl(F& f, std::integer_sequence<int, k...>) {
  (f(std::integral_constant<int, k>{}), ...);
}
// Calls f(integral_constant<int, k>) for k in [0, count): loops the compiler sees unrolled.
template <int kCount, typename F>
BOUNCE_HD BOUNCE_DENOISE_INLINE void unrolled(F&& f) {
  unrolled_impl(f, std::make_integer_sequence<int, kCount>{});
}

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

// Tap column x + dx * step, replaced by x and masked when kCheckColumns and outside the image.
template <bool kCheckColumns>
BOUNCE_HD BOUNCE_DENOISE_INLINE int tap_column(int x, int offset, int width, float& mask,
                                               float outside) {
  int qx = x + offset;
  if constexpr (kCheckColumns) {
    const bool inside = (qx >= 0) & (qx < width);
    mask = inside ? mask : outside;
    qx = inside ? qx : x;
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
// 3x3 pixels with a surface, to geometry[(taps + light) * stride] (light 0 direct, 1 indirect).
template <int kRadius, bool kIndirect, bool kCheckColumns>
BOUNCE_HD BOUNCE_DENOISE_INLINE void atrous_geometry(const AtrousPass& p,
                                                     const AtrousRows<kRadius>& rows, int x,
                                                     float* geometry, size_t stride) {
  const size_t c = rows.tap[kRadius] + size_t(x);
  const float zp = p.surface.depth[c];
  const float nxp = p.surface.nx[c], nyp = p.surface.ny[c], nzp = p.surface.nz[c];
  const float inv_phi_z =
      kLog2e /
      (p.sigma_depth * float(p.step) * (p.depth_slope[c] + kDepthSlopeFloor * zp) + kDepthEpsilon);
  unrolled<kAtrousTaps<kRadius>>([&](auto k) BOUNCE_DENOISE_LAMBDA_INLINE {
    using Tap = AtrousTap<kRadius, decltype(k)::value>;
    constexpr float kernel = atrous_kernel<kRadius>(Tap::dx) * atrous_kernel<kRadius>(Tap::dy);
    const float log2_kernel = std::log2(kernel);
    const float inv_distance = 1.0f / std::sqrt(float(Tap::dx * Tap::dx + Tap::dy * Tap::dy));
    float mask = rows.tap_mask[Tap::dy + kRadius];
    const int qx = tap_column<kCheckColumns>(x, Tap::dx * p.step, p.width, mask, -1e4f);
    const size_t q = rows.tap[Tap::dy + kRadius] + size_t(qx);
    const float cos_pq = nxp * p.surface.nx[q] + nyp * p.surface.ny[q] + nzp * p.surface.nz[q];
    geometry[size_t(decltype(k)::value) * stride] =
        log2_kernel + mask + normal_log2_weight(cos_pq, p.sigma_normal) -
        std::fabs(p.surface.depth[q] - zp) * (inv_phi_z * inv_distance);
  });
  float vd = 0.0f, vi = 0.0f, vw = 0.0f;
  unrolled<9>([&](auto k) BOUNCE_DENOISE_LAMBDA_INLINE {
    constexpr int dx = decltype(k)::value % 3 - 1, dy = decltype(k)::value / 3 - 1;
    constexpr float hk = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
    float mask = rows.near_mask[dy + 1];
    const int qx = tap_column<kCheckColumns>(x, dx, p.width, mask, 0.0f);
    const size_t q = rows.near[dy + 1] + size_t(qx);
    const float wk = mask * (p.surface.depth[q] > 0.0f ? hk : 0.0f);
    vw += wk;
    vd += wk * p.direct.in_var[q];
    if constexpr (kIndirect) vi += wk * p.indirect.in_var[q];
  });
  const float inv_vw = 1.0f / (vw > 0.0f ? vw : 1.0f);
  constexpr size_t kScales = size_t(kAtrousTaps<kRadius>);
  geometry[kScales * stride] =
      kLog2e / (p.sigma_luminance * std::sqrt(vd * inv_vw) + kLuminanceEpsilon);
  if constexpr (kIndirect)
    geometry[(kScales + 1) * stride] =
        kLog2e / (p.sigma_luminance * std::sqrt(vi * inv_vw) + kLuminanceEpsilon);
}

// One light's pass at pixel x (light 0 direct, 1 indirect), with what atrous_geometry wrote.
// Without kVariance (the last pass) the variance is not filtered.
template <int kRadius, bool kCheckColumns, bool kVariance>
BOUNCE_HD BOUNCE_DENOISE_INLINE void atrous_light(const AtrousPass& p, int light_index,
                                                  const AtrousRows<kRadius>& rows, int x,
                                                  const float* geometry, size_t stride) {
  const AtrousLight& light = light_index ? p.indirect : p.direct;
  const size_t c = rows.tap[kRadius] + size_t(x);
  const float inv_phi = geometry[size_t(kAtrousTaps<kRadius> + light_index) * stride];
  const float lp = luminance_of(light.in.r[c], light.in.g[c], light.in.b[c]);
  constexpr float kCentre = atrous_kernel<kRadius>(0) * atrous_kernel<kRadius>(0);
  float sw = kCentre, sr = kCentre * light.in.r[c], sg = kCentre * light.in.g[c],
        sb = kCentre * light.in.b[c], sv = 0.0f;
  if constexpr (kVariance) sv = kCentre * kCentre * light.in_var[c];
  unrolled<kAtrousTaps<kRadius>>([&](auto k) BOUNCE_DENOISE_LAMBDA_INLINE {
    using Tap = AtrousTap<kRadius, decltype(k)::value>;
    float unused = 0.0f;
    const int qx = tap_column<kCheckColumns>(x, Tap::dx * p.step, p.width, unused, 0.0f);
    const size_t q = rows.tap[Tap::dy + kRadius] + size_t(qx);
    const float r = light.in.r[q], g = light.in.g[q], b = light.in.b[q];
    const float w = exp2_weight(geometry[size_t(decltype(k)::value) * stride] -
                                std::fabs(luminance_of(r, g, b) - lp) * inv_phi);
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

// The whole pass at pixel (x, y), for a launcher that runs one thread per pixel.
template <int kRadius, bool kIndirect, bool kVariance>
BOUNCE_HD inline void atrous_pixel(const AtrousPass& p, int x, int y) {
  const AtrousRows<kRadius> rows = atrous_rows<kRadius>(p, y);
  float geometry[kAtrousGeometry<kRadius>];
  atrous_geometry<kRadius, kIndirect, true>(p, rows, x, geometry, 1);
  atrous_light<kRadius, true, kVariance>(p, 0, rows, x, geometry, 1);
  if constexpr (kIndirect) atrous_light<kRadius, true, kVariance>(p, 1, rows, x, geometry, 1);
}

// ---- Remodulation ---------------------------------------------------------------------------

struct RemodulatePass {
  ConstGBufferView g;
  ConstRestPlanes rest;             // the averages, used at rest
  ConstRgbPlanes direct, indirect;  // filtered
  vec3* out_direct = nullptr;
  vec3* out_indirect = nullptr;  // null without indirect light
};

// Multiplies the filtered light back by its albedo and adds the emission (at rest, kRest: the
// averages); pixels without a surface keep what the techniques wrote. Branch-free, so the CPU's
// loop vectorises.
template <bool kIndirect, bool kRest>
BOUNCE_HD BOUNCE_DENOISE_INLINE void remodulate_pixel(const RemodulatePass& p, size_t i) {
  const bool hit = p.g.hit(i);
  const vec3 f = kRest ? p.rest.factor.get(i) : demodulation_factor(p.g.albedo[i]);
  const vec3 e = kRest ? p.rest.emission.get(i) : p.g.emission[i];
  p.out_direct[i] = pick(hit, p.direct.get(i) * f + e, p.out_direct[i]);
  if constexpr (kIndirect) p.out_indirect[i] = pick(hit, p.indirect.get(i) * f, p.out_indirect[i]);
}

}  // namespace bounce::denoise
