// Kernel bodies of the tiled technique's per-pixel work (README.md "A frame"): the photon gather
// at a pixel, and the shared low-resolution estimate and edge-aware upsampling over it.
// Plain functions over plain views, launched by tiled.cpp through parallel_for_2d.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/image_view.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/lowres_kernels.h"
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

// The shared low-resolution kernels (render/lowres_kernels.h) with the photon gather as the
// per-pixel estimator.
BOUNCE_HD inline void estimate_low_res(const TiledGatherView& v, const LowResView& low, int lx,
                                       int ly) {
  estimate_low_res(v.g, low, lx, ly, [&](int x, int y) { return gather_pixel(v, x, y); });
}

BOUNCE_HD inline bool upsample_pixel(const TiledGatherView& v, const ConstLowResView& low,
                                     const EdgeTest& edges, const UpsampleRow& row,
                                     const ImageView& out, int x, int y) {
  return upsample_pixel(v.g, low, edges, row, out, x, y,
                        [&](int px, int py) { return gather_pixel(v, px, py); });
}

}  // namespace bounce
