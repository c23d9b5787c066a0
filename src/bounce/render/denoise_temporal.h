// The denoiser's temporal pass, per pixel (render/denoise_kernels.h): last frame's history
// reprojected through the G-buffer's motion with SVGF's consistency tests, clipped when the world
// changed, and this frame's demodulated light blended in.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "bounce/render/denoise_kernels.h"
#include "bounce/render/light_change_region.h"

namespace bounce::denoise {

// Reprojected history is kept when its accepted bilinear taps weigh at least this much.
inline constexpr float kMinHistoryWeight = 0.01f;

struct TemporalSettings {
  bool history = false;    // last frame's history may be used (temporal on, no reset)
  bool reproject = false;  // through the motion with consistency tests; else the same pixel (rest)
  bool clip = false;       // clamp the history to this frame's neighbourhood (world changed)
  bool rest_continues = false;  // at rest after a reset or rest: the rest averages continue
  float cap_direct = 0.0f;      // history length cap for direct light (infinite at rest)
  // The cap where direct light's history is clipped (the world changed there): a long average
  // of history clipped to one noisy frame's box lags a moving light (DenoiseSettings::
  // changing_history_max).
  float cap_clipped = 0.0f;
  float cap_indirect = 0.0f;  // and for indirect light
  float clip_gamma = 1.0f;
  float depth_tolerance = 0.0f;
  float normal_tolerance = 0.0f;
  // In motion, this frame's weight in the modulation (DenoiseSettings::modulation_alpha).
  float modulation_alpha = 1.0f;

  // Whether this frame's history is clipped (there is one, and the world changed).
  BOUNCE_HD bool clipped() const { return history && clip; }
  // Whether indirect light keeps any history (a cap of 0: IndirectHistory::kRing while the world
  // changes). Where it keeps none, its history is neither reprojected nor clipped.
  BOUNCE_HD bool keeps_indirect() const { return cap_indirect > 0.0f; }
};

struct TemporalPass {
  ConstGBufferView g;              // this frame's
  const vec3* direct = nullptr;    // direct light with the emission the G-buffer saw
  const vec3* indirect = nullptr;  // null without indirect light
  // Light that joins the emission rather than the light filtered (null: none): the lights the
  // renderer shades apart (DirectSettings::apart), exact in each frame. Averaged with the
  // emission in motion, its history clamped to this frame's neighbourhood (shown_range).
  const vec3* exact = nullptr;
  // Last frame's surfaces: the reprojection reads their depth and object ids, and the rest of what
  // it tests and carries from prev_packed.
  ConstSurfacePlanes prev_surface;
  ConstPackedPlanes prev_packed;
  ConstHistoryPlanes prev;
  const float* prev_length = nullptr;
  // Out: the next history (its light is the filter's input), this frame's surfaces and what the
  // next frame reprojects of them and of the modulation (PackedPlanes), the luminance variance of
  // the light's mean from the moments over the frames, the history length.
  HistoryPlanes next;
  SurfacePlanes surface;
  PackedPlanes packed;
  float* var_direct = nullptr;
  float* var_indirect = nullptr;
  float* length = nullptr;
  // The modulation remodulation reads (RestPlanes): updated in place at rest and after a reset;
  // in motion this frame's, blended with last frame's (prev_packed), reprojected with the history.
  RestPlanes rest;
  int width = 0;
  int height = 0;
  // The size of the previous frame's planes (prev_*): the viewer's resolution scaler changes
  // the size in motion, and the history is reprojected across the change.
  int prev_width = 0;
  int prev_height = 0;
  TemporalSettings s;
  // Where direct light's history is clipped when s.clip: where the lights' change reached (every
  // pixel unless nothing but spot lights changed). Indirect light's is clipped everywhere: light
  // a moved spot sends on reaches beyond its cone.
  LightChangeRegion direct_region;
};

// This frame's light at pixel i (which has a surface), demodulated; emission set apart.
BOUNCE_HD inline void demodulated(const TemporalPass& p, size_t i, vec3& direct, vec3& indirect) {
  const vec3 inv = 1.0f / demodulation_factor(p.g.albedo[i]);
  direct = (p.direct[i] - p.g.emission[i]) * inv;
  indirect = p.indirect ? p.indirect[i] * inv : vec3(0.0f);
}

// What pixel i adds to its remodulated light: the emission, and the exact light (p.exact).
BOUNCE_HD BOUNCE_LANE_INLINE vec3 shown_emission(const TemporalPass& p, size_t i) {
  return p.exact ? p.g.emission[i] + p.exact[i] : p.g.emission[i];
}

// Last frame's history for this frame's pixel (x, y): the normalised sum of the taps kept.
struct Reprojected {
  HistoryTexel h;
  float length = 0.0f;
  bool kept = false;
  bool clipped = false;  // direct light's history clipped to this frame's neighbourhood
  // In motion, last frame's modulation (TemporalPass::prev_packed) through the same taps.
  vec3 factor{0.0f}, emission{0.0f};
};
// The bilinear footprint of this frame's pixel (x, y) in the last frame: a 2 x 2 block of its
// pixels from pixel q (row-major in the last frame) and each one's bilinear weight, in the order
// (0, 0), (1, 0), (0, 1), (1, 1). Pixel centres are at integer + 0.5, and motion is in this
// frame's pixels (scaled to the previous frame's when the size changed). The block is moved
// inside the image where the footprint crosses its border (a 1-pixel-wide image: its second
// column or row reads the first), and a pixel outside the footprint, or outside the image,
// weighs 0. The block's columns and rows are then adjacent in memory: the CPU loads each of its
// rows as one pair (reproject_eight).
struct BilinearTaps {
  int q = 0;
  int dq_x = 1;  // from a column of the block to the next: 1, or 0 in a 1-pixel-wide image
  int dq_y = 0;  // from a row of the block to the next: the width, or 0 in a 1-pixel-high image
  float w[4] = {};
};
BOUNCE_HD BOUNCE_LANE_INLINE BilinearTaps bilinear_taps(const TemporalPass& p, int x, int y,
                                                        size_t i) {
  const vec2 m = p.g.motion[i];
  const float sx = float(p.prev_width) / float(p.width),
              sy = float(p.prev_height) / float(p.height);
  const float px = (float(x) + 0.5f - m.x) * sx - 0.5f, py = (float(y) + 0.5f - m.y) * sy - 0.5f;
  const float fx0 = std::floor(px), fy0 = std::floor(py);
  const float fx = px - fx0, fy = py - fy0;
  // (Clamped as floats first: a far motion vector must not overflow the conversion.)
  const int x0 = int(glm::clamp(fx0, -2.0f, float(p.prev_width))),
            y0 = int(glm::clamp(fy0, -2.0f, float(p.prev_height)));
  const int bx = glm::clamp(x0, 0, glm::max(p.prev_width - 2, 0)),
            by = glm::clamp(y0, 0, glm::max(p.prev_height - 2, 0));
  // The weight of column (row) c of the block: of the footprint's first or second, inside.
  auto weight = [](int c, int first, float f, int size) BOUNCE_LANE_LAMBDA_INLINE {
    const float w = (c == first ? 1.0f - f : 0.0f) + (c == first + 1 ? f : 0.0f);
    return c < size ? w : 0.0f;
  };
  const float wx0 = weight(bx, x0, fx, p.prev_width), wx1 = weight(bx + 1, x0, fx, p.prev_width);
  const float wy0 = weight(by, y0, fy, p.prev_height), wy1 = weight(by + 1, y0, fy, p.prev_height);
  BilinearTaps t;
  t.q = by * p.prev_width + bx;
  t.dq_x = p.prev_width > 1 ? 1 : 0;
  t.dq_y = p.prev_height > 1 ? p.prev_width : 0;
  t.w[0] = wx0 * wy0;
  t.w[1] = wx1 * wy0;
  t.w[2] = wx0 * wy1;
  t.w[3] = wx1 * wy1;
  return t;
}

// Whether last frame's pixel q shows the surface this frame's pixel i sees (SVGF's tests: the
// same object, depth within depth_tolerance relative, normals within normal_tolerance).
BOUNCE_HD BOUNCE_LANE_INLINE bool same_surface(const TemporalPass& p, size_t i, int q) {
  const float z = p.g.depth[i];
  const bool same_object = p.prev_surface.object[q] == p.g.mesh[i];
  const bool near_depth = std::fabs(p.prev_surface.depth[q] - z) <= p.s.depth_tolerance * z;
  const bool near_normal =
      glm::dot(p.prev_packed.normal(size_t(q)), p.g.normal[i]) >= p.s.normal_tolerance;
  return same_object & near_depth & near_normal;
}

// Last frame's history where this frame's pixel (x, y) saw it: the taps of its bilinear
// footprint that show this surface, normalised. Branch-free: a pixel without a surface keeps
// nothing. The taps' index is a 32-bit int (images hold far fewer than 2^31 pixels): with a
// 64-bit one GCC 12 leaves the CPU's row loop scalar. (The CPU runs reproject_eight, the same
// for eight pixels at once where the image allows.)
BOUNCE_HD BOUNCE_LANE_INLINE Reprojected reproject_moved(const TemporalPass& p, int x, int y,
                                                         size_t i) {
  Reprojected r;
  const BilinearTaps taps = bilinear_taps(p, x, y, i);
  float weight = 0.0f;
  unrolled<4>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    constexpr int dx = decltype(k)::value & 1, dy = decltype(k)::value >> 1;
    const int q = taps.q + dx * taps.dq_x + dy * taps.dq_y;
    const float w = same_surface(p, i, q) ? taps.w[k] : 0.0f;
    weight += w;
    r.h.add(w, p.prev.get(size_t(q)));
    r.length += w * p.prev_packed.length(size_t(q));
    r.factor += w * p.prev_packed.factor(size_t(q));
    r.emission += w * p.prev_packed.emission(size_t(q));
  });
  r.kept = (weight >= kMinHistoryWeight) & p.g.hit(i);
  const float inv = r.kept ? 1.0f / weight : 0.0f;
  r.h.direct *= inv;
  r.h.indirect *= p.s.keeps_indirect() ? inv : 0.0f;  // (none kept: zero, as the CPU's rows)
  r.length *= inv;
  r.factor *= inv;
  r.emission *= inv;
  return r;
}

BOUNCE_HD BOUNCE_LANE_INLINE Reprojected reproject(const TemporalPass& p, int x, int y, size_t i) {
  if (p.s.reproject) return reproject_moved(p, x, y, i);
  // At rest the pixel sees the same surface: the same pixel, no filtering, no tests (jittered
  // frames may see another object at an edge, or none, and that is the antialiasing: every
  // frame counts, with or without a surface).
  Reprojected r;
  r.kept = true;
  r.h = p.prev.get(i);
  r.length = p.prev_length[i];
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
// The box of n pixels whose light sums to s1 and its squares to s2 (no pixels: a zero box).
BOUNCE_HD BOUNCE_LANE_INLINE ColorBox color_box(float n, vec3 s1, vec3 s2) {
  ColorBox b;
  const float inv = 1.0f / glm::max(n, 1.0f);
  b.mean = s1 * inv;
  b.sigma = glm::sqrt(glm::max(s2 * inv - b.mean * b.mean, vec3(0.0f)));
  return b;
}
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
  return {color_box(n, d1, d2), color_box(n, i1, i2)};
}

// Clamps a history colour (rgb, mean squared luminance) into mean +- gamma sigma, keeping the
// moments' variance.
BOUNCE_HD inline void clip_history(const ColorBox& box, float gamma, vec4& color) {
  const vec3 clipped =
      glm::clamp(vec3(color), box.mean - gamma * box.sigma, box.mean + gamma * box.sigma);
  const float l0 = luminance_of(vec3(color)), l = luminance_of(clipped);
  color = vec4(clipped, color.w + l * l - l0 * l0);
}

// shown_emission demodulated: a beam on a textured wall is then as smooth as its light.
BOUNCE_HD BOUNCE_LANE_INLINE vec3 shown_demodulated(const TemporalPass& p, size_t i) {
  return shown_emission(p, i) / demodulation_factor(p.g.albedo[i]);
}

// The range (per channel) of shown_demodulated over the 3x3 pixels around (x, y) with a surface:
// the history of the exact light of a moving light is clamped into it (demodulated by the
// history's own factor: clamp_shown), as temporal antialiasing clamps a history (Karis 2014): an
// edge's range holds both sides, so jittered frames average there, while a moved beam's old
// light, outside the range, goes.
struct ShownRange {
  vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};

  BOUNCE_HD BOUNCE_LANE_INLINE void add(bool counts, vec3 e) {
    lo = pick(counts, glm::min(lo, e), lo);
    hi = pick(counts, glm::max(hi, e), hi);
  }
  // `e` clamped into the range; unchanged where the range is empty.
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 clamp(vec3 e) const { return glm::min(glm::max(e, lo), hi); }
  // A history's shown emission `e` with its modulation factor `f`, clamped demodulated. (A
  // history not kept has f 0: its value is not used, but must stay finite.)
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 clamp_shown(vec3 e, vec3 f) const {
    const vec3 safe = glm::max(f, vec3(1e-6f));
    return clamp(e / safe) * safe;
  }
};
BOUNCE_HD inline ShownRange shown_range(const TemporalPass& p, int x, int y) {
  ShownRange r;
  for (int qy = glm::max(y - 1, 0); qy <= glm::min(y + 1, p.height - 1); ++qy)
    for (int qx = glm::max(x - 1, 0); qx <= glm::min(x + 1, p.width - 1); ++qx) {
      const size_t q = size_t(qy) * size_t(p.width) + size_t(qx);
      r.add(p.g.hit(q), shown_demodulated(p, q));
    }
  return r;
}

// The first half of the temporal pass at pixel (x, y): last frame's history where it is kept,
// clipped to this frame's neighbourhood when the world changed.
BOUNCE_HD inline Reprojected temporal_history(const TemporalPass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  // (Reprojection follows surfaces, reproject_moved; at rest a pixel without one keeps averaging.)
  if (!p.s.history) return Reprojected{};
  Reprojected r = reproject(p, x, y, i);
  if (r.kept && p.s.clip) {
    const ColorBoxes boxes = neighbourhood(p, x, y);
    r.clipped = p.direct_region.contains(p.g.position[i]);
    if (r.clipped) clip_history(boxes.direct, p.s.clip_gamma, r.h.direct);
    if (p.indirect && p.s.keeps_indirect())
      clip_history(boxes.indirect, p.s.clip_gamma, r.h.indirect);
    if (p.exact) r.emission = shown_range(p, x, y).clamp_shown(r.emission, r.factor);
  }
  return r;
}

// This frame's demodulated light as planes, for the CPU's clipped rows (their loops then
// vectorise): direct rgb, indirect rgb, each pixel's weight in a neighbourhood (1 with a
// surface, 0 without), and with kExact its shown_demodulated rgb. Without kDirect (no direct
// light's history is clipped) the direct planes are not written; nor are the indirect ones
// without kIndirect.
inline constexpr int kDemodulatedPlanes = 10;
inline constexpr int kDemodulatedLightPlanes = 7;  // those without exact light
template <bool kDirect, bool kIndirect, bool kExact>
BOUNCE_HD BOUNCE_LANE_INLINE void store_demodulated(const TemporalPass& p, size_t i,
                                                    float* const* v) {
  vec3 d, ind;
  demodulated(p, i, d, ind);
  // (Zeros where no surface is: a masked tap adds exactly nothing, whatever light is there.)
  const bool hit = p.g.hit(i);
  d = pick(hit, d, vec3(0.0f));
  ind = pick(hit, ind, vec3(0.0f));
  if constexpr (kDirect) {
    v[0][i] = d.x;
    v[1][i] = d.y;
    v[2][i] = d.z;
  }
  if constexpr (kIndirect) {
    v[3][i] = ind.x;
    v[4][i] = ind.y;
    v[5][i] = ind.z;
  }
  v[6][i] = hit ? 1.0f : 0.0f;
  if constexpr (kExact) {
    const vec3 e = shown_demodulated(p, i);
    v[7][i] = e.x;
    v[8][i] = e.y;
    v[9][i] = e.z;
  }
}

// Calls f(q, mask) for the 3x3 pixels around pixel x of the row whose neighbour rows (y - 1, y,
// y + 1) start at `rows`, row by row: q the pixel's index, mask 0 for one outside the image (a
// row outside has `row_mask` 0 and reads row y; with kChecked a column outside, at the row's ends,
// reads column x). Branch-free, for the CPU's vectorised row loops.
template <bool kChecked, typename F>
BOUNCE_HD BOUNCE_LANE_INLINE void for_neighbours(const size_t (&rows)[3],
                                                 const float (&row_mask)[3], int x, int width,
                                                 F&& f) {
  unrolled<9>([&](auto k) BOUNCE_LANE_LAMBDA_INLINE {
    constexpr int dx = decltype(k)::value % 3 - 1, dy = decltype(k)::value / 3 - 1;
    float mask = row_mask[dy + 1];
    int qx = x + dx;
    if constexpr (kChecked) {
      const bool inside = (qx >= 0) & (qx < width);
      mask = inside ? mask : 0.0f;
      qx = inside ? qx : x;
    }
    f(rows[dy + 1] + size_t(qx), mask);
  });
}

// neighbourhood() at pixel x of the row whose neighbour rows (y - 1, y, y + 1) start at `rows`,
// from store_demodulated's planes: a row outside the image has `row_mask` 0 (and reads row y);
// kChecked tests the columns (the row's ends). The same sums in the same order, branch-free.
// kDirect and kIndirect: which lights' boxes are summed (the other's box is left zero).
template <bool kDirect, bool kIndirect, bool kChecked>
BOUNCE_HD BOUNCE_LANE_INLINE ColorBoxes neighbourhood_planes(const float* const* v,
                                                             const size_t (&rows)[3],
                                                             const float (&row_mask)[3], int x,
                                                             int width) {
  vec3 d1(0.0f), d2(0.0f), i1(0.0f), i2(0.0f);
  float n = 0.0f;
  for_neighbours<kChecked>(rows, row_mask, x, width,
                           [&](size_t q, float mask) BOUNCE_LANE_LAMBDA_INLINE {
                             const float w = mask * v[6][q];
                             if constexpr (kDirect) {
                               const vec3 d = w * vec3(v[0][q], v[1][q], v[2][q]);
                               d1 += d;
                               d2 += d * d;
                             }
                             if constexpr (kIndirect) {
                               const vec3 ind = w * vec3(v[3][q], v[4][q], v[5][q]);
                               i1 += ind;
                               i2 += ind * ind;
                             }
                             n += w;
                           });
  return {color_box(n, d1, d2), color_box(n, i1, i2)};
}

// shown_range() at pixel x of the row, from store_demodulated's planes (with kExact), as
// neighbourhood_planes reads them.
template <bool kChecked>
BOUNCE_HD BOUNCE_LANE_INLINE ShownRange shown_range_planes(const float* const* v,
                                                           const size_t (&rows)[3],
                                                           const float (&row_mask)[3], int x,
                                                           int width) {
  ShownRange r;
  for_neighbours<kChecked>(rows, row_mask, x, width,
                           [&](size_t q, float mask) BOUNCE_LANE_LAMBDA_INLINE {
                             r.add(mask * v[6][q] != 0.0f, vec3(v[7][q], v[8][q], v[9][q]));
                           });
  return r;
}

// A row of temporal_history's results as planes, where the CPU's first half leaves them for the
// second, whose loop then vectorises.
inline constexpr int kReprojectedPlanes = 17;
struct ReprojectedRow {
  // Direct rgb and mean squared luminance, the same of indirect, length, kept, the modulation's
  // factor rgb and emission rgb, clipped.
  float* v[kReprojectedPlanes] = {};

  BOUNCE_HD void store(int x, const Reprojected& r) const {
    for (int c = 0; c < 4; ++c) {
      v[c][x] = r.h.direct[c];
      v[4 + c][x] = r.h.indirect[c];
    }
    v[8][x] = r.length;
    v[9][x] = r.kept ? 1.0f : 0.0f;
    for (int c = 0; c < 3; ++c) {
      v[10 + c][x] = r.factor[c];
      v[13 + c][x] = r.emission[c];
    }
    v[16][x] = r.clipped ? 1.0f : 0.0f;
  }
};

// ReprojectedRow's entry x, read through plain pointers (the vectoriser's need).
BOUNCE_HD BOUNCE_LANE_INLINE Reprojected load_reprojected(const float* const* v, int x) {
  Reprojected r;
  r.h.direct = vec4(v[0][x], v[1][x], v[2][x], v[3][x]);
  r.h.indirect = vec4(v[4][x], v[5][x], v[6][x], v[7][x]);
  r.length = v[8][x];
  r.kept = v[9][x] != 0.0f;
  r.factor = vec3(v[10][x], v[11][x], v[12][x]);
  r.emission = vec3(v[13][x], v[14][x], v[15][x]);
  r.clipped = v[16][x] != 0.0f;
  return r;
}

// The second half at pixel i: blends this frame's demodulated light into the history `r` and
// writes the next history and the filter's inputs. alpha = 1 / (n + 1) with n the (capped)
// history length: a plain running average while n is below the cap. Pixels without a surface
// pass their light through, with no history. Branch-free, so the CPU's row loop vectorises;
// kIndirect and kRest (update the rest averages: at rest and at a reset) are the pass's switches.
// Returns whether the pixel's history is too short for its own variance (the spatial estimate then
// stands in). kExact: the pass has exact light (p.exact); a switch, not a test of the pointer in
// the loop, which GCC then vectorises less well.
// kPack: whether it writes p.packed too (the CPU's rows pack theirs after the blend, with F16C:
// pack_row).
template <bool kIndirect, bool kRest, bool kExact = false, bool kPack = true>
BOUNCE_HD BOUNCE_LANE_INLINE bool temporal_blend(const TemporalPass& p, size_t i,
                                                 const Reprojected& r) {
  const bool hit = p.g.hit(i);
  const vec3 normal = p.g.normal[i];
  const float depth = p.g.depth[i];
  const uint32_t mesh = p.g.mesh[i];
  // A surface that reflects nothing (an emitter's black face) carries no light to filter: a zero
  // normal gives it no weight as an a-trous tap, so its zeros do not darken the surface it sits
  // on (the ceiling around the Cornell box's light).
  const bool filtered = hit & reflects_light(p.g.albedo[i], p.g.f0[i]);
  const vec3 surface_normal = pick(filtered, normal, vec3(0.0f));
  p.surface.depth[i] = pick(hit, depth, 0.0f);
  p.surface.nx[i] = surface_normal.x;
  p.surface.ny[i] = surface_normal.y;
  p.surface.nz[i] = surface_normal.z;
  p.surface.object[i] = pick(hit, mesh, kNoPrimitive);

  const vec3 factor = demodulation_factor(p.g.albedo[i]), emission = p.g.emission[i];
  const vec3 shown = kExact ? emission + p.exact[i] : emission;  // shown_emission
  const vec3 inv = 1.0f / factor;
  const vec3 in_d = p.direct[i];
  const vec3 in_i = kIndirect ? p.indirect[i] : vec3(0.0f);
  const vec3 raw_d = (in_d - emission) * inv, raw_i = in_i * inv;
  // At rest (kRest) every pixel averages its frames, those without a surface too.
  const bool averaged = hit | kRest;
  const bool kept = averaged & r.kept;
  const float cap = r.clipped ? p.s.cap_clipped : p.s.cap_direct;
  const float n = pick(kept, glm::min(r.length + 1.0f, cap), 0.0f);
  const float alpha = 1.0f / (n + 1.0f);
  const float alpha_i = 1.0f / (glm::min(n, p.s.cap_indirect) + 1.0f);
  // This frame as a texel, blended in: colour, squared luminance.
  const float l_d = luminance_of(raw_d), l_i = luminance_of(raw_i);
  // (A cap of 0 keeps no indirect history: this frame's light exactly, whatever the CPU's rows
  // left in the history they did not reproject.)
  const bool kept_i = kept & p.s.keeps_indirect();
  const vec4 h_d = pick(kept, r.h.direct, vec4(0.0f)), h_i = pick(kept_i, r.h.indirect, vec4(0.0f));
  vec4 next_d = h_d + (vec4(raw_d, l_d * l_d) - h_d) * alpha;
  vec4 next_i = h_i + (vec4(raw_i, l_i * l_i) - h_i) * alpha_i;
  vec3 next_factor, next_emission;  // the modulation remodulation reads
  if constexpr (kRest) {
    // The rest average continues where this pixel's history does, else it starts here.
    const bool continues = kept & p.s.rest_continues;
    const vec3 f0 = pick(continues, p.rest.factor.get(i), factor);
    const vec3 e0 = p.rest.emission.get(i);
    const vec3 f1 = f0 + (factor - f0) * alpha;
    next_factor = f1;
    next_emission = pick(continues, e0 + (shown - e0) * alpha, shown);
    // At rest jittered frames see other surfaces at an edge: the light that goes back out is
    // the average of the modulated light (the history times the average factor, plus this
    // frame), divided by the new average factor, so that remodulating by it returns exactly the
    // average of the frames (an average of quotients times an average of factors would not).
    const vec3 inv_f1 = 1.0f / f1;
    const vec3 d = (vec3(h_d) * f0 * (1.0f - alpha) + (in_d - emission) * alpha) * inv_f1;
    const vec3 ind = (vec3(h_i) * f0 * (1.0f - alpha_i) + in_i * alpha_i) * inv_f1;
    next_d = vec4(d, next_d.w);
    next_i = vec4(ind, next_i.w);
  } else {
    // In motion the modulation is blended like the light, but with a fixed weight: jittered
    // frames each see one texel of a texture, or one side of an emitter's edge, in a pixel, and
    // a short average of them comes closer to the pixel's average (docs/benchmarks.md, stop 51).
    // Where the history is not kept (a disocclusion, or none) the pixel takes this frame's.
    const float a = kept ? p.s.modulation_alpha : 1.0f;
    next_factor = r.factor + (factor - r.factor) * a;
    next_emission = r.emission + (shown - r.emission) * a;
  }
  p.rest.factor.set(i, next_factor);
  p.rest.emission.set(i, next_emission);
  // (Without a surface and history, next is this frame's light: what a later frame at rest
  // averages with. In motion the filter's result there is not used: remodulation keeps what the
  // technique wrote, so the history's light serves as the filter's input everywhere.)
  p.next.set(i, {next_d, next_i});
  // The variance of the mean of the frames (the spatial estimate replaces it where n is small).
  const float m1_d = luminance_of(vec3(next_d)), m1_i = luminance_of(vec3(next_i));
  p.var_direct[i] = pick(hit, glm::max(next_d.w - m1_d * m1_d, 0.0f) * alpha, 0.0f);
  p.var_indirect[i] = pick(hit, glm::max(next_i.w - m1_i * m1_i, 0.0f) * alpha_i, 0.0f);
  p.length[i] = n;
  if constexpr (kPack) p.packed.set(i, surface_normal, n, next_factor, next_emission);
  return hit & (n + 1.0f < kShortHistory);
}

// The whole temporal pass at pixel (x, y), for a launcher that runs one thread per pixel.
template <bool kIndirect, bool kRest>
BOUNCE_HD inline bool temporal_pixel(const TemporalPass& p, int x, int y) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  const Reprojected r = temporal_history(p, x, y);
  return p.exact ? temporal_blend<kIndirect, kRest, true>(p, i, r)
                 : temporal_blend<kIndirect, kRest, false>(p, i, r);
}

}  // namespace bounce::denoise
