#include "bounce/render/denoiser.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoise_half.h"
#include "bounce/render/denoise_kernels.h"
#include "bounce/render/denoise_plan.h"
#include "bounce/render/denoise_reproject_cpu.h"
#include "bounce/render/denoise_temporal.h"
#include "bounce/render/denoise_variance.h"

namespace bounce {

using denoise::ConstRgbPlanes;
using denoise::ConstSurfacePlanes;
using denoise::RgbPlanes;
using denoise::SurfacePlanes;

namespace {

// Motion of this many pixels shows as 0 or 1 in the motion view.
constexpr float kMotionViewRange = 8.0f;

// Float planes of one image size, each with kPlanePadding zeros before and after: the a-trous
// border loops read taps beyond the image's first and last rows there (with weight 0) instead of
// clamping their addresses, so they vectorise. The padding covers taps up to 1024 pixels away
// (steps up to 2^7 with 5x5 kernels).
constexpr size_t kPlanePadding = 1024;
// Large allocations start at the same offset within a page, and a row loop that streams through
// a dozen planes at equal offsets stalls on 4K aliasing (a load looks like it depends on a store
// to another plane whose address agrees in its low 12 bits). Each plane therefore starts at its
// own multiple of a cache line within a page, taken in turn.
constexpr size_t kPlaneStagger = 16;  // floats: a cache line
inline size_t next_plane_offset() {
  static std::atomic<size_t> count{0};
  return kPlanePadding + (count++ % (4096 / (kPlaneStagger * sizeof(float)))) * kPlaneStagger;
}
template <int kCount, typename T = float>
struct Planes {
  std::array<std::vector<T>, kCount> planes;
  std::array<size_t, kCount> offset{};  // where each plane's first pixel is
  size_t pixels = 0;
  void resize(size_t n) {
    pixels = n;
    for (int k = 0; k < kCount; ++k) size_plane(k);
  }
  // The first `count` planes sized for n pixels; planes past them already sized for n are kept
  // (a frame that needs fewer does not free them), the others left empty.
  void fit(size_t n, int count) {
    if (pixels != n) {
      for (std::vector<float>& p : planes) p = {};
      pixels = n;
    }
    for (int k = 0; k < count; ++k)
      if (planes[size_t(k)].empty()) size_plane(k);
  }
  void size_plane(int k) {
    offset[size_t(k)] = next_plane_offset();
    planes[size_t(k)].assign(pixels + offset[size_t(k)] + kPlanePadding, T(0));
  }
  T* operator[](int k) { return planes[size_t(k)].data() + offset[size_t(k)]; }
  const T* operator[](int k) const { return planes[size_t(k)].data() + offset[size_t(k)]; }
  RgbPlanes rgb(int first) { return {(*this)[first], (*this)[first + 1], (*this)[first + 2]}; }
  ConstRgbPlanes rgb(int first) const {
    return {(*this)[first], (*this)[first + 1], (*this)[first + 2]};
  }
};

denoise::HistoryPlanes history_planes(Planes<8>& planes) {
  denoise::HistoryPlanes h;
  for (int k = 0; k < 8; ++k) h.c[k] = planes[k];
  return h;
}

// A frame's surfaces: depth, normal and object id.
struct SurfaceBuffers {
  Planes<4> geometry;
  std::vector<uint32_t> object;
  void resize(size_t n) {
    geometry.resize(n);
    object.assign(n, kNoPrimitive);
  }
  SurfacePlanes view() {
    return {geometry[0], geometry[1], geometry[2], geometry[3], object.data()};
  }
  ConstSurfacePlanes view() const {
    return {geometry[0], geometry[1], geometry[2], geometry[3], object.data()};
  }
};

// What the next frame reprojects of a frame (denoise::PackedPlanes).
struct PackedBuffers {
  Planes<denoise::PackedPlanes::kCount, uint32_t> words;
  void resize(size_t n) { words.resize(n); }
  denoise::PackedPlanes view() {
    denoise::PackedPlanes p;
    for (int k = 0; k < denoise::PackedPlanes::kCount; ++k) p.w[k] = words[k];
    return p;
  }
  denoise::ConstPackedPlanes view() const {
    denoise::ConstPackedPlanes p;
    for (int k = 0; k < denoise::PackedPlanes::kCount; ++k) p.w[k] = words[k];
    return p;
  }
};

// The a-trous planes: direct rgb, indirect rgb, their variances.
enum FilterPlane { kFilterDirect = 0, kFilterIndirect = 3, kVarDirect = 6, kVarIndirect = 7 };

// Runs body(y) for every row, rows spread over the cores.
template <typename Body>
void for_rows(int height, const Body& body) {
  parallel_for(
      size_t(height), [&](size_t y) { body(int(y)); }, 2);
}

// Runs a per-pixel body over row y: the columns within `border` of the image's sides with
// column tests, the interior without, in loops the compiler vectorises (a pass reads one set of
// planes and writes another, so iterations are independent).
template <typename Checked, typename Interior>
BOUNCE_LANE_INLINE void row_loop(int width, int border, const Checked& checked,
                                 const Interior& interior) {
  const int x0 = std::min(border, width);
  const int x1 = std::max(width - border, x0);
  BOUNCE_IVDEP
  for (int x = 0; x < x0; ++x) checked(x);
  BOUNCE_IVDEP
  for (int x = x0; x < x1; ++x) interior(x);
  BOUNCE_IVDEP
  for (int x = x1; x < width; ++x) checked(x);
}

// Where a clipped frame clips direct light's history (TemporalPass::direct_region): nowhere (a
// flashlight shaded apart moved, and only indirect light and the exact light's range need this
// frame's neighbourhoods), in the cones of the spots that changed, or everywhere.
enum class DirectClip { kNowhere, kWhere, kEverywhere };

DirectClip direct_clip(const LightChangeRegion& r) {
  if (r.everywhere) return DirectClip::kEverywhere;
  return r.cones > 0 ? DirectClip::kWhere : DirectClip::kNowhere;
}

// Whether a clipped frame clips indirect light's history: everywhere, unless the pass has no
// indirect light or keeps none of its history (a cap of 0, IndirectHistory::kRing).
bool clips_indirect(const denoise::TemporalPass& p) {
  return p.indirect && p.s.keeps_indirect();
}

// This frame's demodulated light into `v`'s planes (denoise::store_demodulated), for
// clip_row's neighbourhoods: direct light's with kDirect (it is clipped somewhere).
template <bool kDirect, bool kIndirect>
void demodulate_pass(const denoise::TemporalPass& pass, float* const* v) {
  for_rows(pass.height, [&](int y) {
    const denoise::TemporalPass p = pass;
    const size_t first = size_t(y) * size_t(p.width);
    if (p.exact) {
      BOUNCE_IVDEP
      for (size_t i = first; i < first + size_t(p.width); ++i)
        denoise::store_demodulated<kDirect, kIndirect, true>(p, i, v);
    } else {
      BOUNCE_IVDEP
      for (size_t i = first; i < first + size_t(p.width); ++i)
        denoise::store_demodulated<kDirect, kIndirect, false>(p, i, v);
    }
  });
}

// Clips the history texel at entry x of four row planes (rgb, mean squared luminance) to `box`
// where `clip` is set (a constant true where every pixel is clipped: the pick folds away).
BOUNCE_LANE_INLINE void clip_entry(float* const* c, int x, const denoise::ColorBox& box,
                                   float gamma, bool clip) {
  const vec4 h0(c[0][x], c[1][x], c[2][x], c[3][x]);
  vec4 h = h0;
  denoise::clip_history(box, gamma, h);
  h = pick(clip, h, h0);
  c[0][x] = h.x;
  c[1][x] = h.y;
  c[2][x] = h.z;
  c[3][x] = h.w;
}

// Whether each pixel of row y lies in the region where direct light's history is clipped
// (TemporalPass::direct_region), cone by cone over the row.
// (Locals and a float mask: through a byte pointer the loop reloads everything and stays scalar.)
void direct_region_row(const LightChangeRegion& r, const vec3* position, int width, float* inside) {
  for (int x = 0; x < width; ++x) inside[x] = 0.0f;
  for (int k = 0; k < r.cones; ++k) {
    const vec3 apex = r.apex[k], axis = r.axis[k];
    const float cos_half = r.cos_outer[k];
    BOUNCE_IVDEP
    for (int x = 0; x < width; ++x)
      inside[x] = pick(in_cone(position[x], apex, axis, cos_half), 1.0f, inside[x]);
  }
}

// Clips the row's reprojected history to this frame's neighbourhoods (the world changed), from
// demodulate_pass's planes: indirect light everywhere, direct light where kDirect says (kWhere:
// where `inside` is set). A history not kept is clipped too: it is not read. Where neither light
// is clipped no neighbourhood is summed.
template <bool kIndirect, DirectClip kDirect>
void clip_row_where(const denoise::TemporalPass& p, const float* const* demodulated, int y,
                    const denoise::ReprojectedRow& row, const float* inside) {
  size_t rows[3];
  float row_mask[3];
  for (int k = 0; k < 3; ++k) {
    const int qy = y + k - 1;
    const bool in_image = qy >= 0 && qy < p.height;
    rows[k] = size_t(in_image ? qy : y) * size_t(p.width);
    row_mask[k] = in_image ? 1.0f : 0.0f;
  }
  float* v[8];
  for (int c = 0; c < 8; ++c) v[c] = row.v[c];
  float* clipped = row.v[16];
  const float gamma = p.s.clip_gamma;
  constexpr bool kClipsDirect = kDirect != DirectClip::kNowhere;
  if constexpr (kClipsDirect || kIndirect) {
    auto clip = [&]<bool kChecked>(int x) BOUNCE_LANE_LAMBDA_INLINE {
      const denoise::ColorBoxes boxes =
          denoise::neighbourhood_planes<kClipsDirect, kIndirect, kChecked>(demodulated, rows,
                                                                           row_mask, x, p.width);
      const bool clip_direct =
          kDirect == DirectClip::kEverywhere || (kClipsDirect && inside[x] != 0.0f);
      if constexpr (kClipsDirect) clip_entry(v, x, boxes.direct, gamma, clip_direct);
      if constexpr (kIndirect) clip_entry(v + 4, x, boxes.indirect, gamma, true);
      clipped[x] = clip_direct ? 1.0f : 0.0f;
    };
    row_loop(
        p.width, 1, [&](int x) BOUNCE_LANE_LAMBDA_INLINE { clip.template operator()<true>(x); },
        [&](int x) BOUNCE_LANE_LAMBDA_INLINE { clip.template operator()<false>(x); });
  } else {
    std::fill_n(clipped, p.width, 0.0f);
  }
  if (!p.exact) return;
  // The shown emission's history into its range (denoise::shown_range).
  float* e[3] = {row.v[13], row.v[14], row.v[15]};
  const float* f[3] = {row.v[10], row.v[11], row.v[12]};
  auto clamp = [&]<bool kChecked>(int x) BOUNCE_LANE_LAMBDA_INLINE {
    const denoise::ShownRange r =
        denoise::shown_range_planes<kChecked>(demodulated, rows, row_mask, x, p.width);
    const vec3 c = r.clamp_shown(vec3(e[0][x], e[1][x], e[2][x]), vec3(f[0][x], f[1][x], f[2][x]));
    e[0][x] = c.x;
    e[1][x] = c.y;
    e[2][x] = c.z;
  };
  row_loop(
      p.width, 1, [&](int x) BOUNCE_LANE_LAMBDA_INLINE { clamp.template operator()<true>(x); },
      [&](int x) BOUNCE_LANE_LAMBDA_INLINE { clamp.template operator()<false>(x); });
}

// clip_row_where with direct light clipped in the pass's direct_region.
template <bool kIndirect>
void clip_row(const denoise::TemporalPass& p, const float* const* demodulated, int y,
              const denoise::ReprojectedRow& row) {
  switch (direct_clip(p.direct_region)) {
    case DirectClip::kEverywhere:
      clip_row_where<kIndirect, DirectClip::kEverywhere>(p, demodulated, y, row, nullptr);
      return;
    case DirectClip::kNowhere:
      clip_row_where<kIndirect, DirectClip::kNowhere>(p, demodulated, y, row, nullptr);
      return;
    case DirectClip::kWhere:
      break;
  }
  thread_local std::vector<float> inside_row;
  inside_row.resize(size_t(p.width));
  direct_region_row(p.direct_region, p.g.position + size_t(y) * size_t(p.width), p.width,
                    inside_row.data());
  clip_row_where<kIndirect, DirectClip::kWhere>(p, demodulated, y, row, inside_row.data());
}

// Row y's reprojected history (denoise::reproject_moved at every pixel) into `row`: eight pixels
// at a time where the CPU and the image allow (denoise::reproject_eight).
void reproject_row(const denoise::TemporalPass& pass, int y, const denoise::ReprojectedRow& row) {
  const denoise::TemporalPass p = pass;  // (a local copy: the row's stores cannot change it)
  const size_t first = size_t(y) * size_t(p.width);
  int x = 0;
#if BOUNCE_REPROJECT_EIGHT
  if (denoise::reproject_eight_fits(p)) {
    thread_local std::vector<float> tap_planes;
    thread_local std::vector<int> tap_q;
    tap_planes.resize(7 * size_t(p.width));
    tap_q.resize(size_t(p.width));
    const denoise::TapRow taps =
        denoise::TapRow::over(tap_q.data(), tap_planes.data(), size_t(p.width));
    BOUNCE_IVDEP
    for (int k = 0; k < p.width; ++k) taps.store(p, k, y, first + size_t(k));
    for (; x + 8 <= p.width; x += 8) denoise::reproject_eight(p, taps, x, y, row);
  }
#endif
  // (The row's last pixels, or every pixel without AVX2 or in a 1-pixel-wide or -high image.)
  BOUNCE_IVDEP
  for (; x < p.width; ++x) row.store(x, denoise::reproject_moved(p, x, y, first + size_t(x)));
}

// The temporal pass row by row: the reprojected history into row planes (clipped where the world
// changed, from `demodulated`'s planes), then the blend, in loops the compiler vectorises. Marks
// the rows with a short history. kExact: the pass has exact light (TemporalPass::exact).
template <bool kIndirect, bool kRest, bool kExact>
void temporal_pass(const denoise::TemporalPass& pass, const float* const* demodulated,
                   std::vector<uint8_t>& row_short) {
  for_rows(pass.height, [&](int y) {
    const denoise::TemporalPass p = pass;
    const size_t first = size_t(y) * size_t(p.width);
    uint32_t any_short = 0;  // (a bool reduction would not vectorise)
    if (!p.s.history) {
      // No history to reproject (a reset): every pixel starts from nothing.
      const denoise::Reprojected none;
      BOUNCE_IVDEP
      for (int x = 0; x < p.width; ++x)
        any_short |= uint32_t(
            denoise::temporal_blend<kIndirect, kRest, kExact, false>(p, first + size_t(x), none));
    } else if (!p.s.reproject) {
      // At rest every pixel keeps its own history (denoise::reproject): read it in place.
      BOUNCE_IVDEP
      for (int x = 0; x < p.width; ++x) {
        const size_t i = first + size_t(x);
        denoise::Reprojected same;
        same.h = p.prev.get(i);
        same.length = p.prev_length[i];
        same.kept = true;
        any_short |= uint32_t(denoise::temporal_blend<kIndirect, kRest, kExact, false>(p, i, same));
      }
    } else {
      constexpr int kPlanes = denoise::kReprojectedPlanes;
      thread_local std::vector<float> row_planes;
      row_planes.resize(kPlanes * size_t(p.width));
      denoise::ReprojectedRow row;
      for (int c = 0; c < kPlanes; ++c) row.v[c] = row_planes.data() + size_t(c) * size_t(p.width);
      reproject_row(p, y, row);
      if (p.s.clip)
        clips_indirect(p) ? clip_row<true>(p, demodulated, y, row)
                          : clip_row<false>(p, demodulated, y, row);
      else
        std::fill_n(row.v[16], p.width, 0.0f);
      const float* v[kPlanes];
      for (int c = 0; c < kPlanes; ++c) v[c] = row.v[c];
      BOUNCE_IVDEP
      for (int x = 0; x < p.width; ++x)
        any_short |= uint32_t(denoise::temporal_blend<kIndirect, kRest, kExact, false>(
            p, first + size_t(x), denoise::load_reprojected(v, x)));
    }
    row_short[size_t(y)] = any_short != 0;
    denoise::pack_row(p, y);
  });
}

template <bool kIndirect, bool kRest>
void remodulate_pass(const denoise::RemodulatePass& pass, int height, int width) {
  for_rows(height, [&](int y) {
    const denoise::RemodulatePass p = pass;
    const size_t first = size_t(y) * size_t(width);
    BOUNCE_IVDEP
    for (size_t i = first; i < first + size_t(width); ++i)
      denoise::remodulate_pixel<kIndirect, kRest>(p, i);
  });
}

// One a-trous pass, row by row: the taps' geometric exponents and the lights' luminance scales
// into a row buffer, then each light's filter reading them.
template <int kRadius, bool kIndirect, bool kVariance, bool kLuminanceDirect,
          bool kLuminanceIndirect>
void atrous_pass(const denoise::AtrousPass& pass) {
  for_rows(pass.height, [&](int y) {
    const denoise::AtrousPass p = pass;
    const denoise::AtrousRows<kRadius> rows = denoise::atrous_rows<kRadius>(p, y);
    thread_local std::vector<float> geometry_row;
    const size_t stride = size_t(p.width);
    geometry_row.resize(size_t(denoise::kAtrousGeometry<kRadius>) * stride);
    float* geometry = geometry_row.data();
    const int border = kRadius * p.step;
    constexpr denoise::Columns kMasked = denoise::Columns::kMasked;
    constexpr denoise::Columns kInside = denoise::Columns::kInside;
    row_loop(
        p.width, border,
        [&](int x) BOUNCE_LANE_LAMBDA_INLINE {
          denoise::atrous_geometry<kRadius, kIndirect, kMasked, kLuminanceDirect,
                                   kLuminanceIndirect>(p, rows, x, geometry + x, stride);
        },
        [&](int x) BOUNCE_LANE_LAMBDA_INLINE {
          denoise::atrous_geometry<kRadius, kIndirect, kInside, kLuminanceDirect,
                                   kLuminanceIndirect>(p, rows, x, geometry + x, stride);
        });
    auto light = [&]<bool kLuminance>(int index) {
      constexpr bool kFiltered = kVariance && kLuminance;
      row_loop(
          p.width, border,
          [&](int x) BOUNCE_LANE_LAMBDA_INLINE {
            denoise::atrous_light<kRadius, kMasked, kFiltered, kLuminance>(p, index, rows, x,
                                                                           geometry + x, stride);
          },
          [&](int x) BOUNCE_LANE_LAMBDA_INLINE {
            denoise::atrous_light<kRadius, kInside, kFiltered, kLuminance>(p, index, rows, x,
                                                                           geometry + x, stride);
          });
    };
    light.template operator()<kLuminanceDirect>(0);
    if constexpr (kIndirect) light.template operator()<kLuminanceIndirect>(1);
  });
}

// The depth slope of every pixel (denoise_variance.h) of a w x h depth plane.
void compute_depth_slope(const float* depth, int w, int h, float* slope) {
  for_rows(h, [&](int y) {
    const size_t row = size_t(y) * size_t(w);
    const size_t up = y > 0 ? row - size_t(w) : row, down = y + 1 < h ? row + size_t(w) : row;
    row_loop(
        w, 1,
        [&](int x) BOUNCE_LANE_LAMBDA_INLINE {
          slope[row + size_t(x)] = denoise::depth_slope_pixel<true>(depth, w, row, up, down, x);
        },
        [&](int x) BOUNCE_LANE_LAMBDA_INLINE {
          slope[row + size_t(x)] = denoise::depth_slope_pixel<false>(depth, w, row, up, down, x);
        });
  });
}

// Box sums of radius kRadius along a row of `width` entries, from the row padded with kRadius
// zeros at each end (a loop the compiler vectorises).
template <int kRadius>
void padded_row_sums(const float* padded, int width, float* out) {
  BOUNCE_IVDEP
  for (int x = 0; x < width; ++x) {
    float s = 0.0f;
    for (int d = 0; d <= 2 * kRadius; ++d) s += padded[x + d];
    out[x] = s;
  }
}

// Into `out`, the sums of rows y - kRadius .. y + kRadius (clamped to the image) of the five
// planes `sums`, each a row buffer of width entries.
template <int kRadius>
void column_sums(const float* const (&sums)[5], size_t width, int y, int height, float* out) {
  const int y0 = std::max(y - kRadius, 0), y1 = std::min(y + kRadius, height - 1);
  for (int k = 0; k < 5; ++k) {
    float* o = out + size_t(k) * width;
    std::copy_n(sums[k] + size_t(y0) * width, width, o);
    for (int qy = y0 + 1; qy <= y1; ++qy) {
      const float* in = sums[k] + size_t(qy) * width;
      BOUNCE_IVDEP
      for (size_t x = 0; x < width; ++x) o[x] += in[x];
    }
  }
}

// The spatial variance's row sums for row y (denoise_variance.h), on the CPU: each pixel's
// moments once into a padded row, then each box as a sum over that row, in a loop the compiler
// vectorises (box_row_pixel gathers its box's texels per pixel instead).
void box_row(const denoise::BoxPass& pass, int y) {
  const denoise::BoxPass p = pass;  // (a local copy and plain pointers: the loops vectorise)
  constexpr int r = denoise::kVarianceBox;
  const size_t n = size_t(p.width) + 2 * r;
  thread_local std::vector<float> moments;
  moments.resize(5 * n);
  float* m[5];
  for (int k = 0; k < 5; ++k) {
    m[k] = moments.data() + size_t(k) * n;
    // (Only the r entries at each end stay zero; the loop below writes the rest.)
    std::fill(m[k], m[k] + r, 0.0f);
    std::fill(m[k] + n - r, m[k] + n, 0.0f);
  }
  const size_t row = size_t(y) * size_t(p.width);
  BOUNCE_IVDEP
  for (int x = 0; x < p.width; ++x) {
    float v[5];
    denoise::box_moments(p.history.get(row + size_t(x)), p.depth[row + size_t(x)], v);
    m[0][x + r] = v[0];
    m[1][x + r] = v[1];
    m[2][x + r] = v[2];
    m[3][x + r] = v[3];
    m[4][x + r] = v[4];
  }
  for (int k = 0; k < 5; ++k) padded_row_sums<r>(m[k], p.width, p.sums[k] + row);
}

// The spatial variance of row y: the column sums of the row sums into a row buffer, then
// box_variance over the row. Each is a loop over the row the compiler vectorises (summing the
// column inside the pixel loop would leave it scalar).
void box_column(const denoise::VariancePass& pass, int y) {
  const denoise::VariancePass p = pass;  // (a local copy: the loop vectorises)
  const size_t w = size_t(p.width), row = size_t(y) * w;
  thread_local std::vector<float> columns;
  columns.resize(5 * w);
  column_sums<denoise::kVarianceBox>(p.sums, w, y, p.height, columns.data());
  const float* c[5];
  for (int k = 0; k < 5; ++k) c[k] = columns.data() + size_t(k) * w;
  BOUNCE_IVDEP
  for (size_t x = 0; x < w; ++x) {
    const float s[5] = {c[0][x], c[1][x], c[2][x], c[3][x], c[4][x]};
    denoise::box_variance(p, row + x, s);
  }
}

}  // namespace

int indirect_iterations_for(int iterations, int height) {
  if (iterations <= 0 || height <= 0) return 0;
  // Photon blotches are as wide as the gather radius seen from the camera, which in pixels
  // grows with the image height (the camera's field of view is vertical).
  const int scaled = iterations + int(std::lround(std::log2(double(height) / 512.0)));
  return std::clamp(scaled, 1, 8);
}

int direct_iterations_at_rest(int iterations, int fade_frames, int rest_frames) {
  if (iterations <= 1 || fade_frames <= 0) return iterations;
  int passes = iterations;
  // (64-bit: doubling must not overflow for any frame count)
  for (int64_t f = fade_frames; f <= rest_frames && passes > 1; f *= 2) --passes;
  return passes;
}

namespace {

// The CPU's passes for the schedules both backends share (denoise_plan.h).
struct CpuPasses {
  float* const* half_rows;  // 5 half-resolution planes: half_variance's row sums

  void atrous(const denoise::AtrousPass& pass, bool both, bool variance) const {
    denoise::dispatch_atrous(
        pass, both, variance, [&]<bool... kSwitches>() { atrous_pass<1, kSwitches...>(pass); });
  }
  void depth_slope(const float* depth, int w, int h, float* slope) const {
    compute_depth_slope(depth, w, h, slope);
  }
  void downsample(const denoise::HalfDownsample& p, int half_height) const {
    denoise::with_downsample_switches(p, [&](auto lights, auto moments) {
      downsample_rows<decltype(lights)::value, decltype(moments)::value>(p, half_height);
    });
  }
  // The box summed separably: row sums into half_rows, then per row the column sums into a row
  // buffer and half_box_variance over it.
  void half_variance(const denoise::HalfVariancePass& p) const {
    constexpr int r = denoise::kHalfVarianceBox;
    const size_t w = size_t(p.width);
    for_rows(p.height, [&](int y) {
      thread_local std::vector<float> padded;
      padded.assign(w + 2 * r, 0.0f);
      const size_t row = size_t(y) * w;
      for (int k = 0; k < 5; ++k) {
        std::copy_n(p.moments[k] + row, w, padded.data() + r);
        padded_row_sums<r>(padded.data(), p.width, half_rows[k] + row);
      }
    });
    const float* rows[5];
    for (int k = 0; k < 5; ++k) rows[k] = half_rows[k];
    for_rows(p.height, [&](int y) {
      const denoise::HalfVariancePass v = p;
      thread_local std::vector<float> columns;
      columns.resize(5 * w);
      column_sums<r>(rows, w, y, p.height, columns.data());
      const float* c[5];
      for (int k = 0; k < 5; ++k) c[k] = columns.data() + size_t(k) * w;
      const size_t row = size_t(y) * w;
      BOUNCE_IVDEP
      for (size_t x = 0; x < w; ++x) {
        const float s[5] = {c[0][x], c[1][x], c[2][x], c[3][x], c[4][x]};
        denoise::half_box_variance(v, row + x, s);
      }
    });
  }
  void upsample(const denoise::HalfUpsample& p) const {
    denoise::with_upsample_store(p, [&](const auto& store) { upsample_rows(p, store); });
  }

  template <int kLights, denoise::BlockMoments kMoments>
  static void downsample_rows(const denoise::HalfDownsample& down, int half_height) {
    const int hw = down.half_width;
    for_rows(half_height, [&](int y) {
      const denoise::HalfDownsample p = down;
      // Only the last texel of a row of odd width has a block column outside the image.
      const int interior = p.width % 2 == 0 ? hw : hw - 1;
      BOUNCE_IVDEP
      for (int x = 0; x < interior; ++x)
        denoise::downsample_pixel<false, kLights, kMoments>(p, x, y);
      for (int x = interior; x < hw; ++x)
        denoise::downsample_pixel<true, kLights, kMoments>(p, x, y);
    });
  }
  // Each texel row the row reads is laid out with every texel twice (and the first and last once
  // more at the ends, where texel columns are clamped): pixel x's texel columns hx0 and hx0 + 1
  // are then entries x and x + 2, so the pixel loop reads consecutive entries and vectorises
  // (read in place, texel columns step by half a texel per pixel). Consecutive rows share a
  // texel row, and a thread takes its rows in order: each thread keeps the last two it laid out.
  template <typename Store>
  static void upsample_rows(const denoise::HalfUpsample& up, const Store&) {
    constexpr int kLights = Store::kLights;
    constexpr int kChannels = denoise::kHalfChannels<kLights>;
    static std::atomic<uint64_t> calls{0};
    const uint64_t call = ++calls;  // what a thread's laid-out rows belong to
    for_rows(up.height, [&](int y) {
      const denoise::HalfUpsample p = up;
      const Store store{p};
      const denoise::HalfUpsampleRows rows = denoise::half_upsample_rows(p, y);
      const int hw = p.half_width;
      const size_t n = 2 * size_t(hw) + 2;
      struct LaidOut {
        uint64_t call = 0;
        size_t row = 0;
        std::vector<float> entries;
      };
      thread_local std::array<LaidOut, 2> laid_out;
      const float* source[kChannels];
      denoise::half_channels<kLights>(p, source);
      const auto holding = [&](size_t row) {
        for (int k = 0; k < 2; ++k)
          if (laid_out[size_t(k)].call == call && laid_out[size_t(k)].row == row) return k;
        return -1;
      };
      const float* planes[2][kChannels];
      int kept = -1;  // the slot the first texel row took
      for (int dy = 0; dy < 2; ++dy) {
        const size_t row = rows.row[dy];
        int slot = holding(row);
        if (slot < 0) {
          // Not the slot the first texel row took, nor the one holding the second.
          slot = dy == 1 ? 1 - kept : (holding(rows.row[1]) == 0 ? 1 : 0);
          LaidOut& l = laid_out[size_t(slot)];
          l.call = call;
          l.row = row;
          l.entries.resize(kChannels * n);
          for (int c = 0; c < kChannels; ++c) {
            float* d = l.entries.data() + size_t(c) * n;
            const float* t = source[c] + row;
            BOUNCE_IVDEP
            for (int m = 0; m < hw; ++m) {
              d[1 + 2 * m] = t[m];
              d[2 + 2 * m] = t[m];
            }
            d[0] = t[0];
            d[n - 1] = t[hw - 1];
          }
        }
        if (dy == 0) kept = slot;
        for (int c = 0; c < kChannels; ++c)
          planes[dy][c] = laid_out[size_t(slot)].entries.data() + size_t(c) * n;
      }
      const float* const* row0 = planes[0];
      const float* const* row1 = planes[1];
      // The unfiltered light is read only for the pixels no texel represents, in a second loop:
      // read for every pixel with masked loads, its planes (24 bytes a pixel, from memory at
      // 1280 x 720) were a third of this loop's time.
      thread_local std::vector<uint32_t> missing;  // (as bytes, GCC 12 left the loop scalar)
      missing.resize(size_t(p.width));
      uint32_t any_missing = 0;  // (a bool reduction would not vectorise)
      BOUNCE_IVDEP
      for (int x = 0; x < p.width; ++x) {
        const bool represented = denoise::upsample_from<kLights, false>(
            p, rows, x, y,
            [&](int dx, int dy, const float* const*& c, size_t& h) BOUNCE_LANE_LAMBDA_INLINE {
              c = dy ? row1 : row0;
              h = size_t(x + 2 * dx);  // entry x - 1 or x + 1 of the texels from d + 1
            },
            store);
        missing[size_t(x)] = uint32_t(!represented);
        any_missing |= uint32_t(!represented);
      }
      if (any_missing) {
        const size_t first = size_t(y) * size_t(p.width);
        for (int x = 0; x < p.width; ++x)
          if (missing[size_t(x)]) denoise::upsample_fallback<kLights>(p, first + size_t(x), store);
      }
    });
  }
};

}  // namespace

struct Denoiser::Buffers {
  int width = 0;
  int height = 0;
  bool valid = false;         // a previous run left a history of this size
  bool had_indirect = false;  // and it had indirect light
  bool rest_valid = false;    // the last run left rest averages (it was at rest or a reset)
  int rest_frames = 0;        // consecutive runs at rest up to the last one
  SurfaceBuffers surface, prev_surface;
  PackedBuffers packed, prev_packed;  // kept and swapped with the surfaces
  Planes<8> history, prev_history;    // denoise::HistoryPlanes
  std::vector<float> prev_length;     // last run's history_length_
  // RestPlanes: factor rgb, emission rgb; at rest updated in place, while reprojecting written
  // from last frame's (TemporalPass::prev_packed).
  Planes<6> rest;
  // This frame's demodulated light where the history is clipped (denoise::store_demodulated).
  Planes<denoise::kDemodulatedPlanes> demodulated;
  Planes<5> box;  // its moments summed along rows, for the spatial variance
  std::vector<float> depth_slope;
  std::vector<uint8_t> row_short;  // per row: some pixel's history is short
  std::vector<uint8_t> row_box;    // per row: its box sums are needed
  Planes<2> variance;              // the variance estimate: direct, indirect
  Planes<8> filter[2];             // a-trous ping-pong
  int history_frames = 0;          // frames since the last reset before this run's (0: it is one)
  // Light at half resolution (denoise_half.h): surfaces, depth slope, light and variance (the
  // downsampled input, then a ping-pong pair; the filter planes' layout), the upsampled result
  // (direct rgb, indirect rgb: denoise::HalfPlanes' slots).
  int half_width = 0;
  int half_height = 0;
  SurfaceBuffers half_surface;
  std::vector<float> half_slope;
  Planes<8> half_light[3];
  Planes<10> half_box;         // the spatial variance at half resolution: moments, row sums
  bool half_variance = false;  // the last run estimated it there (the variance view reads it)
  Planes<6> upsampled;
  std::vector<vec2> motion;                  // kept for the debug view
  Image raw_direct, raw_indirect, denoised;  // kept for the debug views

  // Sizes every plane for w x h. With `keep_last`, the last run's surfaces and history (surface,
  // history and the Denoiser's history length) stay at their old size: this run reprojects them
  // across the size change. Otherwise nothing is valid any more.
  void resize(int w, int h, bool keep_last) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h);
    if (!keep_last) {
      surface.resize(n);
      packed.resize(n);
      history.resize(n);
    }
    prev_surface.resize(n);
    prev_packed.resize(n);
    prev_history.resize(n);
    prev_length.assign(n, 0.0f);
    rest.resize(n);
    box.resize(n);
    depth_slope.assign(n, 0.0f);
    row_short.assign(size_t(h), 0);
    row_box.assign(size_t(h), 0);
    variance.resize(n);
    filter[0].resize(n);
    filter[1].resize(n);
    half_width = (w + 1) / 2;
    half_height = (h + 1) / 2;
    const size_t half_n = size_t(half_width) * size_t(half_height);
    half_surface.resize(half_n);
    half_slope.assign(half_n, 0.0f);
    for (auto& planes : half_light) planes.resize(half_n);
    half_box.resize(half_n);
    half_variance = false;
    upsampled.resize(n);
    valid = valid && keep_last;
  }

  denoise::FullPlanes full_planes() {
    denoise::FullPlanes f;
    for (int k = 0; k < 2; ++k) {
      f.direct[k] = filter[k].rgb(kFilterDirect);
      f.indirect[k] = filter[k].rgb(kFilterIndirect);
      f.direct_var[k] = filter[k][kVarDirect];
      f.indirect_var[k] = filter[k][kVarIndirect];
    }
    return f;
  }

  denoise::HalfPlanes half_planes() {
    denoise::HalfPlanes h;
    h.surface = half_surface.view();
    h.depth_slope = half_slope.data();
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < denoise::kHalfMaxLights; ++l) {
        h.light[k][l] = half_light[k].rgb(3 * l);
        h.variance[k][l] = half_light[k][kVarDirect + l];
      }
    for (int l = 0; l < denoise::kHalfMaxLights; ++l) h.upsampled[l] = upsampled.rgb(3 * l);
    for (int k = 0; k < 5; ++k) h.moments[k] = half_box[k];
    h.width = half_width;
    h.height = half_height;
    return h;
  }
};

Denoiser::Denoiser() : buffers_(std::make_unique<Buffers>()) {
  DenoiseSettings& s = settings_;
  params_.add_bool("temporal", &s.temporal, "accumulate light over frames through reprojection");
  params_.add_bool("spatial", &s.spatial, "edge-avoiding a-trous filter of the light");
  params_.add_int("atrous_iterations", &s.atrous_iterations, 0, 8,
                  "a-trous passes over direct light, with steps 1, 2, 4, ... pixels");
  params_.add_int("rest_atrous_frames", &s.rest_atrous_frames, 0, 1 << 20,
                  "frames at rest after which direct light gets one a-trous pass fewer, and one "
                  "fewer per doubling (0: never)");
  params_.add_int("half_direct_frames", &s.half_direct_frames, 0, 1 << 20,
                  "frames after a reset during which direct light is filtered at half "
                  "resolution with one a-trous pass fewer, as it is while the world changes "
                  "(0: never)");
  params_.add_int("indirect_iterations", &s.indirect_iterations, 0, 8,
                  "a-trous passes over indirect light at 512 pixels of image height "
                  "(one more per doubling)");
  params_.add_int("rest_indirect_frames", &s.rest_indirect_frames, 0, 1 << 20,
                  "frames at rest after which indirect light gets one a-trous pass fewer "
                  "(0: never)");
  params_.add_int("indirect_resolution", &s.indirect_resolution, 1, 2,
                  "indirect light is filtered at 1/N of the width and height (1 or 2)");
  params_.add_float("sigma_luminance", &s.sigma_luminance, 0.01, 1000.0,
                    "luminance edge-stopping, in standard deviations of the estimate");
  params_.add_float("sigma_luminance_indirect", &s.sigma_luminance_indirect, 0.0, 1e6,
                    "the same for indirect light; 0: none, by geometry alone (photon blotches "
                    "are wide)");
  params_.add_float("sigma_normal", &s.sigma_normal, 1.0, 1024.0,
                    "normal edge-stopping exponent on the cosine between normals");
  params_.add_float("sigma_depth", &s.sigma_depth, 0.01, 1000.0,
                    "depth edge-stopping, relative to the local depth slope");
  params_.add_int("history_max", &s.history_max, 1, 4096,
                  "frames of history a pixel keeps while anything moves");
  params_.add_int("changing_history_max", &s.changing_history_max, 1, 4096,
                  "the same where the world changed and the history is clipped (direct light "
                  "where the lights' change reached, indirect light everywhere; at most "
                  "history_max)");
  params_.add_int("accumulated_history", &s.accumulated_history, 1, 4096,
                  "frames of history for indirect light the technique accumulates itself, "
                  "while the camera moves");
  params_.add_float("clip_gamma", &s.clip_gamma, 0.0, 100.0,
                    "history clamp half-width in standard deviations when the world changed");
  params_.add_float("modulation_alpha", &s.modulation_alpha, 0.01, 1.0,
                    "in motion, this frame's weight in the albedo and emission light is "
                    "remodulated with (1: this frame's alone)");
  params_.add_float("depth_tolerance", &s.depth_tolerance, 0.0, 10.0,
                    "reprojection: largest relative depth difference of the same surface");
  params_.add_float("normal_tolerance", &s.normal_tolerance, -1.0, 1.0,
                    "reprojection: smallest cosine between normals of the same surface");
}

Denoiser::~Denoiser() = default;

void Denoiser::run(const DenoiseFrame& frame, Image& direct, Image* indirect) {
  const GBuffer& gbuffer = frame.gbuffer;
  const int w = gbuffer.width, h = gbuffer.height;
  if (direct.width() != w || direct.height() != h)
    fail("denoiser: direct light is {}x{}, the G-buffer {}x{}", direct.width(), direct.height(), w,
         h);
  if (indirect && (indirect->width() != w || indirect->height() != h))
    fail("denoiser: indirect light is {}x{}, the G-buffer {}x{}", indirect->width(),
         indirect->height(), w, h);
  Buffers& b = *buffers_;
  const size_t n = size_t(w) * size_t(h);
  const bool has_indirect = indirect != nullptr;
  HistoryState state = frame.state;
  // The size of the last run's surfaces and history, which this run reprojects from.
  int prev_width = w, prev_height = h;
  if (b.width != w || b.height != h) {
    // A history to reproject from survives a size change (the viewer's resolution scaler).
    const bool keep_last = b.valid && state != HistoryState::kReset && settings_.temporal;
    if (keep_last) {
      prev_width = b.width;
      prev_height = b.height;
    }
    b.resize(w, h, keep_last);
    if (!keep_last) history_length_.assign(n, 0.0f);
  }
  const bool resized = prev_width != w || prev_height != h;
  if (!b.valid || b.had_indirect != has_indirect) state = HistoryState::kReset;
  b.valid = true;
  b.had_indirect = has_indirect;
  // Copies of this frame's input for the raw and motion views, dropped when not asked for.
  b.raw_direct = keep_raw_ ? direct : Image();
  b.raw_indirect = keep_raw_ && indirect ? *indirect : Image();
  if (keep_motion_)
    b.motion.assign(gbuffer.motion.begin(), gbuffer.motion.end());
  else
    b.motion.clear();
  const DenoiseSettings& s = settings_;
  const bool rest = denoise::denoise_at_rest(s, state);
  const denoise::TemporalSettings temporal_settings =
      denoise::temporal_settings(s, state, frame.indirect_history, resized, b.rest_valid);
  const float cap_indirect = temporal_settings.cap_indirect;
  // Last run's "next" is this run's "previous". Where each pixel reads its own history (at rest)
  // the history and its length are updated in place instead: one stream through memory, not two.
  std::swap(b.surface, b.prev_surface);
  std::swap(b.packed, b.prev_packed);
  const bool in_place = temporal_settings.history && !temporal_settings.reproject;
  if (!in_place) {
    std::swap(b.history, b.prev_history);
    std::swap(history_length_, b.prev_length);
  }
  Planes<8>& prev_history = in_place ? b.history : b.prev_history;
  std::vector<float>& prev_length = in_place ? history_length_ : b.prev_length;
  // Rest averages start at a reset (the first frame of a still; unless no frame will continue
  // its history) and continue at rest.
  const bool update_rest = rest || (state == HistoryState::kReset && frame.history_continues);
  {
    ScopedStage stage(frame.times, "denoise/temporal");
    denoise::TemporalPass temporal;
    temporal.g = gbuffer.view();
    temporal.direct = direct.data();
    temporal.indirect = indirect ? indirect->data() : nullptr;
    temporal.exact = frame.exact ? frame.exact->pixels().data() : nullptr;
    temporal.prev_surface = std::as_const(b.prev_surface).view();
    temporal.prev_packed = std::as_const(b.prev_packed).view();
    temporal.prev = history_planes(prev_history);
    temporal.prev_length = prev_length.data();
    temporal.next = history_planes(b.history);
    temporal.surface = b.surface.view();
    temporal.packed = b.packed.view();
    temporal.var_direct = b.variance[0];
    temporal.var_indirect = b.variance[1];
    temporal.length = history_length_.data();
    temporal.width = w;
    temporal.height = h;
    temporal.prev_width = prev_width;
    temporal.prev_height = prev_height;
    temporal.s = temporal_settings;
    temporal.direct_region = frame.direct_region;
    temporal.rest = {b.rest.rgb(0), b.rest.rgb(3)};
    float* demodulated[denoise::kDemodulatedPlanes] = {};
    const bool clips_direct = direct_clip(frame.direct_region) != DirectClip::kNowhere;
    if (temporal_settings.history && temporal_settings.clip &&
        (clips_direct || clips_indirect(temporal) || temporal.exact)) {
      // (Sized on the first frame that needs them: a still or camera-only scene never does, and
      // the exact light's on the first frame with exact light.)
      const int planes =
          temporal.exact ? denoise::kDemodulatedPlanes : denoise::kDemodulatedLightPlanes;
      b.demodulated.fit(n, planes);
      for (int k = 0; k < planes; ++k) demodulated[k] = b.demodulated[k];
      auto demodulate = [&]<bool kDirect, bool kIndirect>() {
        demodulate_pass<kDirect, kIndirect>(temporal, demodulated);
      };
      if (clips_indirect(temporal))
        clips_direct ? demodulate.template operator()<true, true>()
                     : demodulate.template operator()<false, true>();
      else
        clips_direct ? demodulate.template operator()<true, false>()
                     : demodulate.template operator()<false, false>();
    }
    auto pass = [&]<bool kIndirect, bool kRest>() {
      temporal.exact ? temporal_pass<kIndirect, kRest, true>(temporal, demodulated, b.row_short)
                     : temporal_pass<kIndirect, kRest, false>(temporal, demodulated, b.row_short);
    };
    if (has_indirect)
      update_rest ? pass.template operator()<true, true>()
                  : pass.template operator()<true, false>();
    else
      update_rest ? pass.template operator()<false, true>()
                  : pass.template operator()<false, false>();
  }
  b.rest_valid = update_rest;
  // Every pixel's history is at least this long (at rest each one keeps its own, unless the size
  // changed); saturates.
  b.rest_frames = rest && !resized ? denoise::next_count(b.rest_frames) : 0;
  b.history_frames = state == HistoryState::kReset ? 0 : denoise::next_count(b.history_frames);

  // The filter's input: the accumulated demodulated light, the history's.
  const denoise::HistoryPlanes history = history_planes(b.history);
  ConstRgbPlanes light_d = history.direct_light();
  ConstRgbPlanes light_i = history.indirect_light();
  const bool spatial = s.spatial && s.atrous_iterations > 0;
  const denoise::AtrousPlan plan = denoise::atrous_plan(
      s, spatial, has_indirect, h, b.rest_frames, b.history_frames, temporal_settings.clipped());
  b.half_variance = plan.half_variance;
  if (spatial) {
    ScopedStage stage(frame.times, "denoise/variance");
    // The depth slope the a-trous depth weights are relative to.
    const float* depth = b.surface.geometry[0];
    compute_depth_slope(depth, w, h, b.depth_slope.data());
    // (With the plan's half_variance, the half-resolution filter estimates it: filter_half.)
    if (!plan.half_variance) {
      // Box sums for rows within the box's radius of a row with a short history, then the spatial
      // estimate on those rows.
      for (int y = 0; y < h; ++y) {
        bool needed = false;
        for (int k = std::max(y - denoise::kVarianceBox, 0);
             k <= std::min(y + denoise::kVarianceBox, h - 1); ++k)
          needed |= b.row_short[size_t(k)] != 0;
        b.row_box[size_t(y)] = needed;
      }
      denoise::BoxPass box;
      box.history = history;
      box.depth = depth;
      for (int k = 0; k < 5; ++k) box.sums[k] = b.box[k];
      box.width = w;
      for_rows(h, [&](int y) {
        if (!b.row_box[size_t(y)]) return;
        box_row(box, y);
      });
      denoise::VariancePass variance;
      variance.depth = depth;
      variance.length = history_length_.data();
      for (int k = 0; k < 5; ++k) variance.sums[k] = b.box[k];
      variance.var_direct = b.variance[0];
      variance.var_indirect = b.variance[1];
      variance.width = w;
      variance.height = h;
      variance.cap_indirect = cap_indirect;
      for_rows(h, [&](int y) {
        if (!b.row_short[size_t(y)]) return;
        box_column(variance, y);
      });
    }
  }
  // The a-trous passes: at full resolution direct light (with indirect light when both share the
  // passes), then indirect light alone; at half resolution the lights the plan puts there.
  const denoise::AtrousPass base =
      denoise::atrous_base(s, b.surface.view(), b.depth_slope.data(), light_d, b.variance[0],
                           light_i, b.variance[1], w, h);
  float* half_rows[5];
  for (int k = 0; k < 5; ++k) half_rows[k] = b.half_box[5 + k];
  const CpuPasses passes{half_rows};
  if (plan.direct_full) {
    ScopedStage stage(frame.times, "denoise/atrous");
    denoise::filter_direct_full(passes, base, plan, b.full_planes(), light_d, light_i);
  }
  // Remodulation, of the filtered light wherever it ends up.
  denoise::RemodulatePass remodulate{
      gbuffer.view(), {std::as_const(b.rest).rgb(0), std::as_const(b.rest).rgb(3)},
      light_d,        light_i,
      direct.data(),  indirect ? indirect->data() : nullptr};
  if (plan.direct_half || plan.half) {
    // (Both lights at half resolution count as the direct stage, as both at full resolution do;
    // with every light there the upsample remodulates.)
    ScopedStage stage(frame.times, plan.direct_half ? "denoise/atrous" : "denoise/indirect");
    const denoise::HalfVarianceInputs variance{history, history_length_.data(), cap_indirect,
                                               b.history_frames == 0};
    denoise::filter_half(passes, base, plan, b.half_planes(), variance, remodulate, rest, light_d,
                         light_i);
  }
  if (plan.indirect_full) {
    ScopedStage stage(frame.times, "denoise/indirect");
    denoise::filter_indirect_full(passes, base, plan, b.full_planes(), light_i);
  }
  if (!plan.upsample_remodulates) {
    ScopedStage stage(frame.times, "denoise/remodulate");
    remodulate.direct = light_d;
    remodulate.indirect = light_i;
    if (has_indirect)
      rest ? remodulate_pass<true, true>(remodulate, h, w)
           : remodulate_pass<true, false>(remodulate, h, w);
    else
      rest ? remodulate_pass<false, true>(remodulate, h, w)
           : remodulate_pass<false, false>(remodulate, h, w);
  }
  if (keep_raw_) {
    b.denoised = direct;
    if (indirect) b.denoised += *indirect;
  } else {
    b.denoised = Image();
  }
}

void Denoiser::debug_view(DenoiseView view, Image& out) const {
  const Buffers& b = *buffers_;
  const int w = b.width, h = b.height;
  const size_t n = size_t(w) * size_t(h);
  switch (view) {
    case DenoiseView::kDenoised:
    case DenoiseView::kRaw: {
      const bool raw = view == DenoiseView::kRaw;
      if ((raw ? b.raw_direct : b.denoised).empty())
        fail("denoiser: the {} view needs keep_raw(true) before the run", raw ? "raw" : "denoised");
      out = raw ? b.raw_direct : b.denoised;
      if (raw && !b.raw_indirect.empty()) out += b.raw_indirect;
      return;
    }
    default:
      break;
  }
  if (out.width() != w || out.height() != h) out = Image(w, h);
  vec3* pixels = out.data();
  switch (view) {
    case DenoiseView::kHistory: {
      const float inv_max = 1.0f / float(std::max(settings_.history_max, 1));
      parallel_for(
          n, [&](size_t i) { pixels[i] = vec3(std::min(history_length_[i] * inv_max, 1.0f)); });
      return;
    }
    case DenoiseView::kMotion:
      if (b.motion.empty())
        fail("denoiser: the motion view needs keep_motion(true) before the run");
      parallel_for(n, [&](size_t i) {
        const vec2 m = glm::clamp(0.5f + b.motion[i] / (2.0f * kMotionViewRange), 0.0f, 1.0f);
        pixels[i] = vec3(m.x, m.y, 0.0f);
      });
      return;
    case DenoiseView::kVariance: {
      // As a standard deviation, of direct and indirect light together.
      const float* var_d = b.variance[0];
      const float* var_i = b.variance[1];
      const bool has_indirect = b.had_indirect;
      if (b.half_variance) {
        // Estimated at half resolution (of the blocks' means): each pixel shows its texel's.
        const float* half_d = b.half_light[0][kVarDirect];
        const float* half_i = b.half_light[0][kVarIndirect];
        parallel_for(n, [&](size_t i) {
          const size_t t = (i / size_t(w) / 2) * size_t(b.half_width) + (i % size_t(w)) / 2;
          pixels[i] = vec3(std::sqrt(half_d[t] + (has_indirect ? half_i[t] : 0.0f)));
        });
        return;
      }
      parallel_for(n, [&](size_t i) {
        pixels[i] = vec3(std::sqrt(var_d[i] + (has_indirect ? var_i[i] : 0.0f)));
      });
      return;
    }
    default:
      return;
  }
}

}  // namespace bounce
