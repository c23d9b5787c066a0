// Filtering light at half resolution (render/denoiser.h): photon gathers leave blotches as wide
// as the gather radius, tens of pixels at 512x512, which the full-resolution a-trous filter's five
// passes (a footprint of about 13 pixels' standard deviation) cannot flatten. The same passes over
// a half-resolution image reach twice as far at a quarter of the cost. Direct light takes the same
// path while its history is short (DenoiseSettings::half_direct_frames), or clipped every frame
// while the world changes: with one frame of one light sample its noise is as wide as the
// full-resolution passes reach.
//
// downsample_pixel builds each half-resolution texel from its 2x2 block: the surface of the
// block's nearest reflecting pixel, and the light and variance of the block's pixels that lie on
// that surface. upsample_pixel is a joint-bilateral upsample: the four nearest texels, weighted
// bilinearly and by depth and normal agreement with the full-resolution pixel; a pixel that no
// texel represents (a sliver thinner than two pixels) keeps its own unfiltered light. Both take
// one or two lights (direct, indirect) through the same surface tests, computed once.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoise_kernels.h"
#include "bounce/render/denoise_variance.h"

namespace bounce::denoise {

// Block pixels on the representative's surface: cosine between normals and relative depth.
inline constexpr float kHalfNormalAgreement = 0.9f;
inline constexpr float kHalfDepthAgreement = 0.05f;
// Below this total weight the upsample keeps the pixel's own light.
inline constexpr float kHalfMinWeight = 1e-3f;

// The lights a half-resolution pass carries at most (direct and indirect).
inline constexpr int kHalfMaxLights = 2;

// Where a half-resolution block's moments for the spatial variance come from: none (the variance
// is the full-resolution estimate's), the history, or, when every pixel holds one frame (a
// reset), the light itself (its luminance, squared for the second moment; what the history holds
// then, without reading it).
enum class BlockMoments { kNone, kOneFrame, kHistory };

struct HalfDownsample {
  ConstSurfacePlanes surface;            // full resolution
  int lights = 1;                        // how many entries of light, variance, half_* are used
  ConstRgbPlanes light[kHalfMaxLights];  // full resolution, demodulated
  const float* variance[kHalfMaxLights] = {};
  int width = 0;  // full resolution
  int height = 0;
  SurfacePlanes half_surface;  // half resolution (object ids unused)
  RgbPlanes half_light[kHalfMaxLights];
  float* half_variance[kHalfMaxLights] = {};
  int half_width = 0;
  // Unless `moments` is kNone, the spatial variance is estimated at half resolution
  // (denoise_variance.h): the block's moments (box_moments, of all its pixels) are summed into
  // half_moments, and half_variance receives the scale half_box_variance multiplies the box's
  // variance by, instead of the variance of the full-resolution estimates (`variance` unread).
  BlockMoments moments = BlockMoments::kNone;
  ConstHistoryPlanes history;     // kHistory: the accumulation, with its moments
  const float* length = nullptr;  // kHistory: history length per pixel
  float cap_indirect = 0.0f;
  float* half_moments[5] = {};
};

// Half-resolution texel hx of row hy, for the first kLights lights. kClampX: the block's second
// column may lie outside an image of odd width (the last texel of a row; the row loop's other
// texels need no test). kMoments: p.moments. Branch-free, so the CPU's row loop vectorises.
template <bool kClampX, int kLights, BlockMoments kMoments>
BOUNCE_HD BOUNCE_LANE_INLINE void downsample_pixel(const HalfDownsample& p, int hx, int hy) {
  const int x0 = 2 * hx, y0 = 2 * hy;
  const int x1 = kClampX && x0 + 1 >= p.width ? x0 : x0 + 1;
  const int y1 = y0 + 1 < p.height ? y0 + 1 : y0;
  const size_t r0 = size_t(y0) * size_t(p.width), r1 = size_t(y1) * size_t(p.width);
  const size_t block[4] = {r0 + size_t(x0), r0 + size_t(x1), r1 + size_t(x0), r1 + size_t(x1)};
  // The representative: the nearest pixel whose surface is filtered (a non-zero normal).
  float rep_depth = 1e30f, nx = 0.0f, ny = 0.0f, nz = 0.0f;
  unrolled<4>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    const size_t q = block[decltype(k)::value];
    const float z = p.surface.depth[q];
    const float qx = p.surface.nx[q], qy = p.surface.ny[q], qz = p.surface.nz[q];
    const bool nearer = (z > 0.0f) & (qx * qx + qy * qy + qz * qz > 0.0f) & (z < rep_depth);
    rep_depth = nearer ? z : rep_depth;
    nx = nearer ? qx : nx;
    ny = nearer ? qy : ny;
    nz = nearer ? qz : nz;
  });
  const bool found = rep_depth < 1e30f;
  float r[kLights] = {}, g[kLights] = {}, b[kLights] = {}, var[kLights] = {}, count = 0.0f;
  float moments[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  unrolled<4>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    const size_t q = block[decltype(k)::value];
    const float z = p.surface.depth[q];
    const float cos_q = nx * p.surface.nx[q] + ny * p.surface.ny[q] + nz * p.surface.nz[q];
    const bool same = (z > 0.0f) & (cos_q >= kHalfNormalAgreement) &
                      (std::fabs(z - rep_depth) <= kHalfDepthAgreement * rep_depth);
    const float w = same ? 1.0f : 0.0f;
    float pixel_var[kHalfMaxLights] = {};
    if constexpr (kMoments == BlockMoments::kHistory) {
      float m[5];
      box_moments(p.history.get(q), z, m);
      for (int c = 0; c < 5; ++c) moments[c] += m[c];
      float frames_d, frames_i;
      averaged_frames(p.length[q], p.cap_indirect, frames_d, frames_i);
      pixel_var[0] = 1.0f / frames_d;
      pixel_var[1] = 1.0f / frames_i;
    } else if constexpr (kMoments == BlockMoments::kOneFrame) {
      const float on = z > 0.0f ? 1.0f : 0.0f;
      unrolled<kLights>([&](auto l) BOUNCE_LANE_LAMBDA_INLINE {
        constexpr int kL = decltype(l)::value;
        const float m1 = on * luminance_of(p.light[kL].get(q));
        moments[2 * kL] += m1;
        moments[2 * kL + 1] += m1 * m1;
        pixel_var[kL] = 1.0f;
      });
      moments[4] += on;
    } else {
      unrolled<kLights>([&](auto l) BOUNCE_LANE_LAMBDA_INLINE {
        pixel_var[decltype(l)::value] = p.variance[decltype(l)::value][q];
      });
    }
    unrolled<kLights>([&](auto l) BOUNCE_LANE_LAMBDA_INLINE {
      constexpr int kL = decltype(l)::value;
      r[kL] += w * p.light[kL].r[q];
      g[kL] += w * p.light[kL].g[q];
      b[kL] += w * p.light[kL].b[q];
      var[kL] += w * pixel_var[kL];
    });
    count += w;
  });
  // (Where a representative was found it counts itself, so count >= 1.)
  const float inv = found ? 1.0f / (count > 0.0f ? count : 1.0f) : 0.0f;
  const size_t h = size_t(hy) * size_t(p.half_width) + size_t(hx);
  p.half_surface.depth[h] = found ? rep_depth : 0.0f;
  p.half_surface.nx[h] = nx;
  p.half_surface.ny[h] = ny;
  p.half_surface.nz[h] = nz;
  unrolled<kLights>([&](auto l) BOUNCE_LANE_LAMBDA_INLINE {
    constexpr int kL = decltype(l)::value;
    p.half_light[kL].r[h] = r[kL] * inv;
    p.half_light[kL].g[h] = g[kL] * inv;
    p.half_light[kL].b[h] = b[kL] * inv;
    // The variance of the block's mean (or, with kMoments, what scales the box's variance to it).
    p.half_variance[kL][h] = var[kL] * inv * inv;
  });
  if constexpr (kMoments != BlockMoments::kNone)
    for (int c = 0; c < 5; ++c) p.half_moments[c][h] = moments[c];
}

// Calls f(lights, moments) with p.lights and p.moments as integral constants: the one dispatch
// of the downsample's switches, for every launcher.
template <typename F>
BOUNCE_HD BOUNCE_LANE_INLINE void with_downsample_switches(const HalfDownsample& p, const F& f) {
  auto with_moments = [&](auto lights) {
    switch (p.moments) {
      case BlockMoments::kNone:
        return f(lights, std::integral_constant<BlockMoments, BlockMoments::kNone>{});
      case BlockMoments::kOneFrame:
        return f(lights, std::integral_constant<BlockMoments, BlockMoments::kOneFrame>{});
      case BlockMoments::kHistory:
        return f(lights, std::integral_constant<BlockMoments, BlockMoments::kHistory>{});
    }
  };
  if (p.lights == 2)
    with_moments(std::integral_constant<int, 2>{});
  else
    with_moments(std::integral_constant<int, 1>{});
}

// The whole downsample at texel (hx, hy), for a launcher that runs one thread per texel.
BOUNCE_HD inline void downsample_pixel(const HalfDownsample& p, int hx, int hy) {
  with_downsample_switches(p, [&](auto lights, auto moments) {
    downsample_pixel<true, decltype(lights)::value, decltype(moments)::value>(p, hx, hy);
  });
}

struct HalfUpsample {
  ConstSurfacePlanes surface;            // full resolution
  const float* depth_slope;              // full resolution
  int lights = 1;                        // how many entries of light, half_light and out are used
  ConstRgbPlanes light[kHalfMaxLights];  // full resolution, unfiltered (the fallback)
  ConstSurfacePlanes half_surface;
  ConstRgbPlanes half_light[kHalfMaxLights];  // filtered
  int width = 0;
  int height = 0;
  int half_width = 0;
  int half_height = 0;
  float sigma_depth = 0.0f;
  RgbPlanes out[kHalfMaxLights];  // full resolution
  // With `remodulated` (nothing is filtered after this), the result goes straight through
  // remodulate_light into the output images instead of `out`; `rest`: remodulate_pixel's kRest.
  // With `indirect_only` the one light here is indirect light, and direct light, filtered
  // already, comes from remodulate.direct.
  bool remodulated = false;
  bool rest = false;
  bool indirect_only = false;
  RemodulatePass remodulate;
};

// Where upsample_from puts pixel i's upsampled lights: `out`, or remodulated.
template <int kCount>
struct UpsampleToPlanes {
  static constexpr int kLights = kCount;
  const HalfUpsample& p;
  BOUNCE_HD BOUNCE_LANE_INLINE void operator()(size_t i, const vec3 (&light)[kLights]) const {
    for (int l = 0; l < kLights; ++l) p.out[l].set(i, light[l]);
  }
};
// kIndirectOnly: the one light is indirect (HalfUpsample::indirect_only).
template <int kCount, bool kRest, bool kIndirectOnly = false>
struct UpsampleRemodulated {
  static constexpr int kLights = kCount;
  const HalfUpsample& p;
  BOUNCE_HD BOUNCE_LANE_INLINE void operator()(size_t i, const vec3 (&light)[kLights]) const {
    if constexpr (kIndirectOnly)
      remodulate_light<true, kRest>(p.remodulate, i, p.remodulate.direct.get(i), light[0]);
    else
      remodulate_light<kLights == 2, kRest>(p.remodulate, i, light[0],
                                            kLights == 2 ? light[kLights - 1] : vec3(0.0f));
  }
};

// The two texel rows a full-resolution row y reads, and their bilinear weights.
struct HalfUpsampleRows {
  size_t row[2];
  float weight[2];
};
BOUNCE_HD inline HalfUpsampleRows half_upsample_rows(const HalfUpsample& p, int y) {
  // Texel centres sit at full-resolution coordinates 2h + 0.5.
  const float fy = 0.5f * (float(y) + 0.5f) - 0.5f;
  const int hy0 = int(std::floor(fy));
  const float ty = fy - float(hy0);
  const int last = p.half_height - 1;
  const int r0 = hy0 < 0 ? 0 : hy0, r1 = hy0 + 1 > last ? last : hy0 + 1;
  return {{size_t(r0) * size_t(p.half_width), size_t(r1) * size_t(p.half_width)}, {1.0f - ty, ty}};
}

// The half image's planes an upsample reads, in one order: depth, normal x, y, z, then each
// light's r, g, b.
template <int kLights>
inline constexpr int kHalfChannels = 4 + 3 * kLights;
template <int kLights>
BOUNCE_HD BOUNCE_LANE_INLINE void half_channels(const HalfUpsample& p,
                                                const float* (&c)[kHalfChannels<kLights>]) {
  c[0] = p.half_surface.depth;
  c[1] = p.half_surface.nx;
  c[2] = p.half_surface.ny;
  c[3] = p.half_surface.nz;
  for (int l = 0; l < kLights; ++l) {
    c[4 + 3 * l] = p.half_light[l].r;
    c[5 + 3 * l] = p.half_light[l].g;
    c[6 + 3 * l] = p.half_light[l].b;
  }
}

// Full-resolution pixel x of row y (rows from half_upsample_rows), for the first kLights lights.
// texel(dx, dy) gives the planes (half_channels' order) and index of texel column hx0 + dx in
// texel row dy, hx0 as below: the launcher decides how texels are laid out. store(i, light)
// puts the result (UpsampleToPlanes, UpsampleRemodulated). Returns whether the texels represent
// the pixel; where they do not, its light is the unfiltered light at full resolution
// (upsample_fallback), or without kFallback whatever: the caller then stores the fallback itself.
template <int kLights, bool kFallback = true, typename Texel, typename Store>
BOUNCE_HD BOUNCE_LANE_INLINE bool upsample_from(const HalfUpsample& p, const HalfUpsampleRows& rows,
                                                int x, int y, const Texel& texel,
                                                const Store& store) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  const float z = p.surface.depth[i];
  const float nx = p.surface.nx[i], ny = p.surface.ny[i], nz = p.surface.nz[i];
  // Even columns sit a quarter texel right of a texel centre (hx0 = x / 2 - 1), odd ones a
  // quarter left (hx0 = x / 2).
  const float tx = (x & 1) ? 0.25f : 0.75f;
  // A texel counts where it lies on this pixel's surface: its normal within the block test's
  // cosine, and its depth within what the local slope allows over the two pixels its centre can
  // be away (plus the block test's relative margin). Plain tests, not exponentials: this runs
  // for every pixel, and the filtered light varies slowly anyway. The slope is capped: a sliver
  // between two depth edges has a steep slope by its neighbours, not by its own surface.
  const float slope = glm::min(p.depth_slope[i], kHalfDepthAgreement * z);
  const float max_dz = (2.0f * p.sigma_depth * slope) + kHalfDepthAgreement * z;
  float r[kLights] = {}, g[kLights] = {}, b[kLights] = {}, wsum = 0.0f;
  unrolled<4>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    constexpr int dx = decltype(k)::value & 1, dy = decltype(k)::value >> 1;
    const float* const* c = nullptr;
    size_t h = 0;
    texel(dx, dy, c, h);
    const float bilinear = (dx ? tx : 1.0f - tx) * rows.weight[dy];
    const float zh = c[0][h];
    const float cos_nh = nx * c[1][h] + ny * c[2][h] + nz * c[3][h];
    const bool same =
        (zh > 0.0f) & (cos_nh >= kHalfNormalAgreement) & (std::fabs(zh - z) <= max_dz);
    const float w = same ? bilinear : 0.0f;
    unrolled<kLights>([&](auto l) BOUNCE_LANE_LAMBDA_INLINE {
      constexpr int kL = decltype(l)::value;
      r[kL] += w * c[4 + 3 * kL][h];
      g[kL] += w * c[5 + 3 * kL][h];
      b[kL] += w * c[6 + 3 * kL][h];
    });
    wsum += w;
  });
  const bool represented = (z > 0.0f) & (wsum > kHalfMinWeight);
  const float inv = 1.0f / (represented ? wsum : 1.0f);
  vec3 light[kLights];
  unrolled<kLights>([&](auto l) BOUNCE_LANE_LAMBDA_INLINE {
    constexpr int kL = decltype(l)::value;
    light[kL] = vec3(r[kL] * inv, g[kL] * inv, b[kL] * inv);
    if constexpr (kFallback)
      light[kL] = vec3(represented ? light[kL].x : p.light[kL].r[i],
                       represented ? light[kL].y : p.light[kL].g[i],
                       represented ? light[kL].z : p.light[kL].b[i]);
  });
  store(i, light);
  return represented;
}

// Stores pixel i's unfiltered light: the upsample's result where no texel represents the pixel.
template <int kLights, typename Store>
BOUNCE_HD BOUNCE_LANE_INLINE void upsample_fallback(const HalfUpsample& p, size_t i,
                                                    const Store& store) {
  vec3 light[kLights];
  for (int l = 0; l < kLights; ++l) light[l] = p.light[l].get(i);
  store(i, light);
}

// upsample_from reading the half image's planes in place, texel columns clamped to the image.
template <int kLights, typename Store>
BOUNCE_HD inline void upsample_pixel(const HalfUpsample& p, const HalfUpsampleRows& rows, int x,
                                     int y, const Store& store) {
  const float* c[kHalfChannels<kLights>];
  half_channels<kLights>(p, c);
  const int hx0 = (x >> 1) - 1 + (x & 1);
  upsample_from<kLights>(
      p, rows, x, y,
      [&](int dx, int dy, const float* const*& planes, size_t& h) {
        int hx = hx0 + dx;
        hx = hx < 0 ? 0 : (hx >= p.half_width ? p.half_width - 1 : hx);
        planes = c;
        h = rows.row[dy] + size_t(hx);
      },
      store);
}

// Calls f(store) with the store `p` asks for: f is templated on the lights and the store.
template <typename F>
BOUNCE_HD BOUNCE_LANE_INLINE void with_upsample_store(const HalfUpsample& p, const F& f) {
  if (p.lights == 2) {
    if (!p.remodulated) return f(UpsampleToPlanes<2>{p});
    return p.rest ? f(UpsampleRemodulated<2, true>{p}) : f(UpsampleRemodulated<2, false>{p});
  }
  if (!p.remodulated) return f(UpsampleToPlanes<1>{p});
  if (p.indirect_only)
    return p.rest ? f(UpsampleRemodulated<1, true, true>{p})
                  : f(UpsampleRemodulated<1, false, true>{p});
  return p.rest ? f(UpsampleRemodulated<1, true>{p}) : f(UpsampleRemodulated<1, false>{p});
}

// The whole upsample at pixel (x, y), for a launcher that runs one thread per pixel.
BOUNCE_HD inline void upsample_pixel(const HalfUpsample& p, int x, int y) {
  with_upsample_store(p, [&](const auto& store) {
    using Store = std::decay_t<decltype(store)>;
    upsample_pixel<Store::kLights>(p, half_upsample_rows(p, y), x, y, store);
  });
}

}  // namespace bounce::denoise
