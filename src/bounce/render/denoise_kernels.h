// What the denoiser's per-pixel bodies share (render/denoiser.h): the planes they read and write,
// the history texel, the edge-stopping arithmetic, and remodulation. The bodies themselves are in
// denoise_temporal.h (reprojection and accumulation), denoise_variance.h (depth slope, spatial
// variance) and denoise_atrous.h (the wavelet filter). They work on structure-of-arrays float
// planes, so the CPU's row loops (denoiser.cpp) vectorise; a GPU launcher calls the same bodies
// once per pixel.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "bounce/core/device.h"
#include "bounce/core/half_float.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#if !BOUNCE_DEVICE_CODE
#include <bit>  // exp2_weight
#endif

namespace bounce::denoise {

// An albedo at or below this in every channel is "black": light is not demodulated there.
inline constexpr float kAlbedoFloor = 1e-3f;
// A channel is demodulated by at least this fraction of the albedo's brightest channel.
inline constexpr float kChannelFloor = 0.05f;
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

// The history of every pixel as eight planes, in HistoryTexel's order (direct rgb and mean
// squared luminance, then indirect), so that the CPU's row loops load and store it as vectors.
template <bool kConst>
struct HistoryPlanesT {
  Ptr<float, kConst> c[8] = {};

  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator HistoryPlanesT<kTo>() const {
    HistoryPlanesT<kTo> to;
    for (int k = 0; k < 8; ++k) to.c[k] = c[k];
    return to;
  }
  // The accumulated light of direct and of indirect light: the a-trous filter's input.
  BOUNCE_HD RgbPlanesT<kConst> direct_light() const { return {c[0], c[1], c[2]}; }
  BOUNCE_HD RgbPlanesT<kConst> indirect_light() const { return {c[4], c[5], c[6]}; }
  BOUNCE_HD HistoryTexel get(size_t i) const {
    return {vec4(c[0][i], c[1][i], c[2][i], c[3][i]), vec4(c[4][i], c[5][i], c[6][i], c[7][i])};
  }
  BOUNCE_HD void set(size_t i, const HistoryTexel& t) const {
    // (Written out: a loop over the planes keeps the row loop from vectorising.)
    c[0][i] = t.direct.x;
    c[1][i] = t.direct.y;
    c[2][i] = t.direct.z;
    c[3][i] = t.direct.w;
    c[4][i] = t.indirect.x;
    c[5][i] = t.indirect.y;
    c[6][i] = t.indirect.z;
    c[7][i] = t.indirect.w;
  }
};
using HistoryPlanes = HistoryPlanesT<false>;
using ConstHistoryPlanes = HistoryPlanesT<true>;

// The demodulation factor and the emission averaged over the frames at rest, so that jittered
// frames, which see several surfaces in an edge pixel, converge to the average of what they saw;
// in motion, over the last few frames (temporal_blend).
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

// What the next frame's reprojection reads of a pixel besides its history, depth and object id,
// as pairs of halves (core/half_float.h): the normal the surface tests compare and the history
// length (nx | ny, nz | length), then the modulation (factor r | g, factor b | emission r,
// emission g | b). The temporal pass writes them beside the full-precision planes that the other
// passes read: the reprojection's gathers then touch five planes where they touched ten, and its
// time goes with the cache lines it touches (docs/benchmarks.md, stop 56). Half precision is
// 1/2048 of a value; the length (at most history_max in motion) clamps at 65504.
template <bool kConst>
struct PackedPlanesT {
  static constexpr int kCount = 5;
  Ptr<uint32_t, kConst> w[kCount] = {};

  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator PackedPlanesT<kTo>() const {
    PackedPlanesT<kTo> to;
    for (int k = 0; k < kCount; ++k) to.w[k] = w[k];
    return to;
  }
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 normal(size_t i) const {
    return {low_half(w[0][i]), high_half(w[0][i]), low_half(w[1][i])};
  }
  BOUNCE_HD BOUNCE_LANE_INLINE float length(size_t i) const { return high_half(w[1][i]); }
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 factor(size_t i) const {
    return {low_half(w[2][i]), high_half(w[2][i]), low_half(w[3][i])};
  }
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 emission(size_t i) const {
    return {high_half(w[3][i]), low_half(w[4][i]), high_half(w[4][i])};
  }
  BOUNCE_HD BOUNCE_LANE_INLINE void set(size_t i, vec3 normal, float length, vec3 factor,
                                        vec3 emission) const {
    w[0][i] = pack_halves(normal.x, normal.y);
    w[1][i] = pack_halves(normal.z, length);
    w[2][i] = pack_halves(factor.x, factor.y);
    w[3][i] = pack_halves(factor.z, emission.x);
    w[4][i] = pack_halves(emission.y, emission.z);
  }
};
using PackedPlanes = PackedPlanesT<false>;
using ConstPackedPlanes = PackedPlanesT<true>;

BOUNCE_HD inline float luminance_of(float r, float g, float b) {
  return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}
BOUNCE_HD inline float luminance_of(vec3 c) {
  return luminance_of(c.x, c.y, c.z);
}

// Whether a surface reflects any light (some albedo or specular channel above black).
BOUNCE_HD inline bool reflects_light(vec3 albedo, vec3 f0) {
  return glm::max(max_component(albedo), max_component(f0)) > kAlbedoFloor;
}

// What light is divided by: the albedo, each channel at least kChannelFloor times its brightest
// channel (continuous in the albedo), or 1 where every channel is black (an emitter, a mirror:
// their light is not the albedo's). With 1 for each black channel instead, a dark texture whose
// blue crossed the floor from texel to texel divided on one side and not on the other, and the
// filters, which mix neighbours' demodulated light, gave the pixels below the floor their
// neighbours' incident light back undivided: specks of pure colour. A floor of absolute size
// would amplify light that is not the albedo's (a highlight in a black channel) a thousandfold.
BOUNCE_HD inline vec3 demodulation_factor(vec3 albedo) {
  const float top = glm::max(albedo.x, glm::max(albedo.y, albedo.z));
  const bool black = !(top > kAlbedoFloor);
  const float low = kChannelFloor * top;
  return {black ? 1.0f : (albedo.x > low ? albedo.x : low),
          black ? 1.0f : (albedo.y > low ? albedo.y : low),
          black ? 1.0f : (albedo.z > low ? albedo.z : low)};
}

// 2^x for x <= 0, and exactly 0 below -126: the filter's weights. On the CPU a cubic (relative
// error 1e-4, plenty for a weight) that vectorises.
BOUNCE_HD BOUNCE_LANE_INLINE float exp2_weight(float x) {
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
BOUNCE_HD BOUNCE_LANE_INLINE float normal_log2_weight(float cos_pq, float sigma_normal) {
  const float t = 1.0f - cos_pq;
  return -(sigma_normal * kLog2e) * t * (1.0f + t * (0.5f + t * (1.0f / 3.0f))) +
         (cos_pq > 0.0f ? 0.0f : -1e4f);
}

template <typename F, int... k>
BOUNCE_HD BOUNCE_LANE_INLINE void unrolled_impl(F& f, std::integer_sequence<int, k...>) {
  (f(std::integral_constant<int, k>{}), ...);
}
// Calls f(integral_constant<int, k>) for k in [0, count): loops the compiler sees unrolled.
template <int kCount, typename F>
BOUNCE_HD BOUNCE_LANE_INLINE void unrolled(F&& f) {
  unrolled_impl(f, std::make_integer_sequence<int, kCount>{});
}

struct RemodulatePass {
  ConstGBufferView g;
  // The albedo factor and emission to remodulate with: averaged over the frames at rest, and in
  // motion over the last frames (denoise_temporal.h, temporal_blend).
  ConstRestPlanes rest;
  ConstRgbPlanes direct, indirect;  // filtered
  vec3* out_direct = nullptr;
  vec3* out_indirect = nullptr;  // null without indirect light
};

// Multiplies pixel i's filtered light back by its albedo factor and adds the emission (p.rest's);
// at rest (kRest) every pixel, in motion only pixels with a surface (the others keep what the
// techniques wrote).
// Branch-free, so the CPU's loop vectorises.
template <bool kIndirect, bool kRest>
BOUNCE_HD BOUNCE_LANE_INLINE void remodulate_light(const RemodulatePass& p, size_t i, vec3 direct,
                                                   vec3 indirect) {
  // At rest every pixel holds an average, those without a surface this frame too.
  const bool averaged = p.g.hit(i) | kRest;
  const vec3 f = p.rest.factor.get(i), e = p.rest.emission.get(i);
  p.out_direct[i] = pick(averaged, direct * f + e, p.out_direct[i]);
  if constexpr (kIndirect) p.out_indirect[i] = pick(averaged, indirect * f, p.out_indirect[i]);
}

// The same with the filtered light from p's planes.
template <bool kIndirect, bool kRest>
BOUNCE_HD BOUNCE_LANE_INLINE void remodulate_pixel(const RemodulatePass& p, size_t i) {
  remodulate_light<kIndirect, kRest>(p, i, p.direct.get(i),
                                     kIndirect ? p.indirect.get(i) : vec3(0.0f));
}

}  // namespace bounce::denoise
