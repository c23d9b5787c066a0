// Photons binned into screen tiles (seed 000 §5.3.3.1, after Mara et al. 2013): each tile's
// sub-frustum, bounded by the nearest and farthest depth of its pixels, is tested against each
// photon's sphere of influence; a tile lists the photons whose sphere reaches it. Count, prefix
// sum, insert: the lists are exact and their order is photon order, whatever the thread count.
// The bodies are in tile_bins_kernels.h; this class owns the arrays and launches them.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/photons.h"
#include "bounce/scene/camera.h"
#include "bounce/techniques/tiled/tile_bins_kernels.h"

namespace bounce {

class TileBins {
 public:
  // Bins for the G-buffer's pixels in tiles of tile x tile pixels.
  void build(const GBuffer& g, const CameraRays& camera, const PhotonBuffer& photons, float radius,
             int tile);

  int tile_size() const { return grid_.tile; }
  int tiles_x() const { return grid_.tiles_x; }
  int tiles_y() const { return grid_.tiles_y; }
  size_t tile_of_pixel(int x, int y) const { return grid_.tile_of_pixel(x, y); }
  // The photons of tile t: indices into the photon buffer.
  const uint32_t* begin(size_t t) const { return indices_.data() + offsets_[t]; }
  const uint32_t* end(size_t t) const { return indices_.data() + offsets_[t + 1]; }
  size_t entries() const { return indices_.size(); }
  // Valid until the next build.
  TileBinsView view() const { return {offsets_.data(), indices_.data(), grid_}; }

 private:
  TileGrid grid_;
  std::vector<TileFrustum> frusta_;
  std::vector<ivec2> photon_tiles_x_;  // inclusive tile column range of each photon's bounds
  std::vector<ivec2> photon_tiles_y_;  // inclusive tile row range
  std::vector<uint32_t> row_first_;    // per photon: its first row entry
  std::vector<uint32_t> row_keys_;     // row entries (row, photon), sorted by row
  std::vector<uint32_t> row_photons_;
  std::vector<uint32_t> row_start_;  // tiles_y + 1 offsets into the row entries
  std::vector<uint32_t> counts_;     // per tile: photons counted, then inserted
  std::vector<uint32_t> offsets_;
  std::vector<uint32_t> indices_;
};

}  // namespace bounce
