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

// Bilinear upsampling of the low-resolution estimate to pixel (x, y) of row `row`; where the
// interpolated normal or position disagrees with the pixel's own (an edge), or a contributing
// sample missed, the pixel is estimated at full resolution. Writes out(x, y); returns whether it
// was an edge.
template <typename Estimate>
BOUNCE_HD inline bool upsample_pixel(const ConstGBufferView& g, const ConstLowResView& low,
                                     const EdgeTest& edges, const UpsampleRow& row,
                                     const ImageView& out, int x, int y, const Estimate& estimate) {
  const size_t i = g.index(x, y);
  if (!g.hit(i)) {
    out.at(x, y) = vec3(0.0f);
    return false;
  }
  const float gx = (float(x) + 0.5f) / float(low.factor) - 0.5f;
  const int lx0 = glm::clamp(int(std::floor(gx)), 0, low.width - 1);
  const int lx1 = glm::min(lx0 + 1, low.width - 1);
  const float fx = glm::clamp(gx - float(lx0), 0.0f, 1.0f), fy = row.fy;
  const size_t l[4] = {low.index(lx0, row.ly0), low.index(lx1, row.ly0), low.index(lx0, row.ly1),
                       low.index(lx1, row.ly1)};
  const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  bool edge = false;
  vec3 normal(0.0f), position(0.0f), radiance(0.0f);
  for (int k = 0; k < 4; ++k) {
    if (!low.valid[l[k]]) edge = edge || w[k] > 0.0f;
    normal += w[k] * low.normal[l[k]];
    position += w[k] * low.position[l[k]];
    radiance += w[k] * low.radiance[l[k]];
  }
  const float len = glm::length(normal);
  edge = edge || len <= 0.0f || glm::dot(g.normal[i], normal / len) < edges.min_normal_dot ||
         glm::length(g.position[i] - position) > edges.max_gap;
  if (edge) radiance = edges.show_edges ? vec3(1.0f, 1.0f, 0.0f) : estimate(x, y);
  out.at(x, y) = radiance;
  return edge;
}

}  // namespace bounce
