// Indirect light at low resolution with edge-aware upsampling, shared by the techniques whose
// per-pixel estimate is costly (tiled, lhb): one estimate per factor x factor block of pixels,
// bilinear upsampling, and a full-resolution estimate where the block's samples disagree with
// the pixel in normal or position (an edge). The estimator is a plain callable
// `vec3 (int x, int y)` giving full-resolution pixel (x, y)'s indirect radiance; the kernels are
// host/device functions over plain views (lowres_estimate.h launches them on the CPU).
#pragma once

#include <cmath>
#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/image_view.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"

namespace bounce {

// The low-resolution estimate: one sample per factor x factor block of pixels, taken at the
// full-resolution pixel nearest the block's centre, with that pixel's normal and position.
template <bool kConst>
struct LowResViewT {
  template <typename T>
  using Ptr = maybe_const_t<T, kConst>*;

  Ptr<vec3> radiance = nullptr;
  Ptr<vec3> normal = nullptr;
  Ptr<vec3> position = nullptr;
  Ptr<uint8_t> valid = nullptr;  // the sample hit a surface
  int width = 0;
  int height = 0;
  int factor = 2;

  BOUNCE_HD size_t index(int lx, int ly) const { return size_t(ly) * size_t(width) + size_t(lx); }
  // A writable view reads as a read-only one.
  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator LowResViewT<kTo>() const {
    return {radiance, normal, position, valid, width, height, factor};
  }
};
using LowResView = LowResViewT<false>;
using ConstLowResView = LowResViewT<true>;

struct EdgeTest {
  float min_normal_dot = 0.99f;  // re-estimate below this agreement of normals
  float max_gap = 0.0f;          // ... or beyond this distance between positions
  bool show_edges = false;       // mark re-estimated pixels yellow instead (debug view)
  // Re-estimate a pixel whose blend takes a sample that missed (a block whose centre sees no
  // surface); else blend only the samples that hit, re-estimating only where none did.
  bool misses = true;
};

// Low-resolution sample (lx, ly): the estimate at the block's centre pixel.
template <typename Estimate>
BOUNCE_HD inline void estimate_low_res(const ConstGBufferView& g, const LowResView& low, int lx,
                                       int ly, const Estimate& estimate) {
  const int f = low.factor;
  const int x = glm::min(lx * f + f / 2, g.width - 1);
  const int y = glm::min(ly * f + f / 2, g.height - 1);
  const size_t i = g.index(x, y), l = low.index(lx, ly);
  low.valid[l] = g.hit(i) ? 1 : 0;
  low.normal[l] = g.normal[i];
  low.position[l] = g.position[i];
  low.radiance[l] = estimate(x, y);
}

// The low-resolution rows (ly0, ly1 = ly0 + 1 clamped) and weight between them that pixel row y
// interpolates; the same for every pixel of the row.
struct UpsampleRow {
  int ly0, ly1;
  float fy;
};
BOUNCE_HD inline UpsampleRow upsample_row(const ConstLowResView& low, int y) {
  const float gy = (float(y) + 0.5f) / float(low.factor) - 0.5f;
  const int ly0 = glm::clamp(int(std::floor(gy)), 0, low.height - 1);
  return {ly0, glm::min(ly0 + 1, low.height - 1), glm::clamp(gy - float(ly0), 0.0f, 1.0f)};
}

// Bilinear upsampling is separable: a row blends each low-resolution column between its two
// low-resolution rows once (upsample_column), and each pixel blends the two columns on either
// side of it (upsample_blend). A CPU row loop computes the row's columns once for all its
// pixels; a GPU thread computes its two.
// The column's sums take only the samples that hit (a sample that missed has weight 0 in them);
// `weight` is what their weights add up to.
struct UpsampleColumn {
  vec3 radiance{0.0f}, normal{0.0f}, position{0.0f};
  float weight = 0.0f;
  bool valid = false;  // every sample with weight in the blend hit a surface
};
BOUNCE_HD inline UpsampleColumn upsample_column(const ConstLowResView& low, const UpsampleRow& row,
                                                int lx) {
  const size_t a = low.index(lx, row.ly0), b = low.index(lx, row.ly1);
  const float f0 = 1.0f - row.fy, f1 = row.fy;
  const bool hit_a = low.valid[a] != 0, hit_b = low.valid[b] != 0;
  const float w0 = hit_a ? f0 : 0.0f, w1 = hit_b ? f1 : 0.0f;
  UpsampleColumn c;
  c.radiance = w0 * low.radiance[a] + w1 * low.radiance[b];
  c.normal = w0 * low.normal[a] + w1 * low.normal[b];
  c.position = w0 * low.position[a] + w1 * low.position[b];
  c.weight = w0 + w1;
  c.valid = (hit_a || !(f0 > 0.0f)) && (hit_b || !(f1 > 0.0f));
  return c;
}

// The two low-resolution columns around pixel column x and the weight of the second.
struct UpsampleSpan {
  int lx0, lx1;
  float fx;
};
BOUNCE_HD inline UpsampleSpan upsample_span(const ConstLowResView& low, int x) {
  const float gx = (float(x) + 0.5f) / float(low.factor) - 0.5f;
  const int lx0 = glm::clamp(int(std::floor(gx)), 0, low.width - 1);
  return {lx0, glm::min(lx0 + 1, low.width - 1), glm::clamp(gx - float(lx0), 0.0f, 1.0f)};
}

// The upsampled light at G-buffer pixel i from its two columns, and whether the pixel is an edge:
// a sample with weight in the blend missed (with edges.misses; else only when every one did),
// or the blended normal or position disagrees with the pixel's own. A pixel without a surface
// gets no light and is no edge.
struct Upsampled {
  vec3 radiance{0.0f};
  bool edge = false;
};
BOUNCE_HD inline Upsampled upsample_blend(const ConstGBufferView& g, const EdgeTest& edges,
                                          size_t i, const UpsampleColumn& c0,
                                          const UpsampleColumn& c1, float fx) {
  const float w0 = 1.0f - fx, w1 = fx;
  const vec3 normal = w0 * c0.normal + w1 * c1.normal;
  const vec3 radiance = w0 * c0.radiance + w1 * c1.radiance;
  const vec3 position = w0 * c0.position + w1 * c1.position;
  // The weight of the samples that hit: all of it when none missed (then nothing is divided, so
  // that such blends stay as they were), else what renormalises the blend over those that hit.
  const float weight = w0 * c0.weight + w1 * c1.weight;
  const bool missed = (!c0.valid && w0 > 0.0f) || (!c1.valid && w1 > 0.0f);
  const bool renormalise = missed && !edges.misses && weight > 0.0f;
  const float scale = renormalise ? 1.0f / weight : 1.0f;
  const vec3 gap = g.position[i] - scale * position;
  const float len = glm::length(normal);
  // The normal test without dividing by the blended normal's length (len > 0 there).
  const bool edge = (missed && !renormalise) || !(len > 0.0f) ||
                    glm::dot(g.normal[i], normal) < edges.min_normal_dot * len ||
                    glm::dot(gap, gap) > edges.max_gap * edges.max_gap;
  const bool hit = g.hit(i);
  Upsampled u;
  u.radiance = hit ? scale * radiance : vec3(0.0f);
  u.edge = hit && edge;
  return u;
}

// What an edge pixel gets: the full-resolution estimate, or yellow in the debug view.
template <typename Estimate>
BOUNCE_HD inline vec3 edge_radiance(const EdgeTest& edges, int x, int y, const Estimate& estimate) {
  return edges.show_edges ? vec3(1.0f, 1.0f, 0.0f) : estimate(x, y);
}

// Bilinear upsampling of the low-resolution estimate to pixel (x, y) of row `row`, estimated at
// full resolution instead where it is an edge (upsample_blend). Writes out(x, y); returns
// whether it was an edge.
template <typename Estimate>
BOUNCE_HD inline bool upsample_pixel(const ConstGBufferView& g, const ConstLowResView& low,
                                     const EdgeTest& edges, const UpsampleRow& row,
                                     const ImageView& out, int x, int y, const Estimate& estimate) {
  const UpsampleSpan span = upsample_span(low, x);
  const Upsampled u = upsample_blend(g, edges, g.index(x, y), upsample_column(low, row, span.lx0),
                                     upsample_column(low, row, span.lx1), span.fx);
  out.at(x, y) = u.edge ? edge_radiance(edges, x, y, estimate) : u.radiance;
  return u.edge;
}

}  // namespace bounce
