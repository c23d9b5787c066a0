// Kernel bodies of the tiled technique's per-pixel work (README.md "A frame"): the photon gather
// at a pixel, the low-resolution estimate, and the bilinear upsampling that re-estimates edges.
// Plain functions over plain views, launched by tiled.cpp through parallel_for_2d.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/image_view.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/photon_gather.h"
#include "bounce/render/photon_hash_grid.h"
#include "bounce/render/photon_view.h"
#include "bounce/techniques/tiled/tile_bins_kernels.h"

namespace bounce {

// Everything a pixel's gather reads: the G-buffer, the photons and one of their two indexes.
struct TiledGatherView {
  ConstGBufferView g;
  ConstPhotonView photons;
  GatherSettings settings;
  bool use_grid = false;  // the hash grid, else the screen tiles
  TileBinsView bins;
  PhotonHashGridView grid;
};
static_assert(std::is_trivially_copyable_v<TiledGatherView>);

// The indirect radiance the photons give full-resolution pixel (x, y); 0 where nothing was hit.
BOUNCE_HD inline vec3 gather_pixel(const TiledGatherView& v, int x, int y) {
  const size_t i = v.g.index(x, y);
  if (!v.g.hit(i)) return vec3(0.0f);
  const vec3 p = v.g.position[i], n = v.g.normal[i];
  vec3 sum(0.0f);
  const auto visit = [&](uint32_t k) {
    const float w = gather_weight(v.photons, k, p, n, v.settings);
    if (w > 0.0f) sum += v.photons.flux[k] * w;
  };
  if (v.use_grid) {
    v.grid.for_each_within(p, v.settings.radius, visit);
  } else {
    const size_t t = v.bins.grid.tile_of_pixel(x, y);
    for (const uint32_t* k = v.bins.begin(t); k != v.bins.end(t); ++k) visit(*k);
  }
  return cone_filter_radiance(sum, v.g.albedo[i], v.settings.radius);
}

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

BOUNCE_HD inline void estimate_low_res(const TiledGatherView& v, const LowResView& low, int lx,
                                       int ly) {
  const int f = low.factor;
  const int x = glm::min(lx * f + f / 2, v.g.width - 1);
  const int y = glm::min(ly * f + f / 2, v.g.height - 1);
  const size_t i = v.g.index(x, y), l = low.index(lx, ly);
  low.valid[l] = v.g.hit(i) ? 1 : 0;
  low.normal[l] = v.g.normal[i];
  low.position[l] = v.g.position[i];
  low.radiance[l] = gather_pixel(v, x, y);
}

struct EdgeTest {
  float min_normal_dot = 0.99f;  // re-estimate below this agreement of normals
  float max_gap = 0.0f;          // ... or beyond this distance between positions
  bool show_edges = false;       // mark re-estimated pixels yellow instead (debug view)
};

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
BOUNCE_HD inline bool upsample_pixel(const TiledGatherView& v, const ConstLowResView& low,
                                     const EdgeTest& edges, const UpsampleRow& row,
                                     const ImageView& out, int x, int y) {
  const size_t i = v.g.index(x, y);
  if (!v.g.hit(i)) {
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
  edge = edge || len <= 0.0f || glm::dot(v.g.normal[i], normal / len) < edges.min_normal_dot ||
         glm::length(v.g.position[i] - position) > edges.max_gap;
  if (edge) radiance = edges.show_edges ? vec3(1.0f, 1.0f, 0.0f) : gather_pixel(v, x, y);
  out.at(x, y) = radiance;
  return edge;
}

}  // namespace bounce
