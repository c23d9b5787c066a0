// Photons binned into screen tiles (seed 000 §5.3.3.1, after Mara et al. 2013): each tile's
// sub-frustum, bounded by the nearest and farthest depth of its pixels, is tested against each
// photon's sphere of influence; a tile lists the photons whose sphere reaches it. Count, prefix
// sum, insert: the lists are exact and their order is photon order, whatever the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/photons.h"
#include "bounce/scene/camera.h"

namespace bounce {

class TileBins {
 public:
  // Bins for the G-buffer's pixels in tiles of tile x tile pixels.
  void build(const GBuffer& g, const CameraRays& camera, const PhotonBuffer& photons, float radius,
             int tile);

  int tile_size() const { return tile_; }
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  size_t tile_of_pixel(int x, int y) const {
    return size_t(y / tile_) * size_t(tiles_x_) + size_t(x / tile_);
  }
  // The photons of tile t: indices into the photon buffer.
  const uint32_t* begin(size_t t) const { return indices_.data() + offsets_[t]; }
  const uint32_t* end(size_t t) const { return indices_.data() + offsets_[t + 1]; }
  size_t entries() const { return indices_.size(); }

 private:
  struct TileFrustum {
    vec3 planes[4];               // unit normals through the eye, pointing out of the tile
    float near_depth, far_depth;  // view depth range of the tile's pixels; empty when near > far
  };
  bool overlaps(const TileFrustum& f, vec3 p_rel_eye, float depth, float radius) const;

  int tile_ = 8;
  int tiles_x_ = 0;
  int tiles_y_ = 0;
  std::vector<TileFrustum> frusta_;
  std::vector<ivec2> photon_tiles_x_;  // inclusive tile column range of each photon's bounds
  std::vector<ivec2> photon_tiles_y_;  // inclusive tile row range
  std::vector<uint32_t> row_start_;    // photons of each tile row, by counting sort
  std::vector<uint32_t> row_photons_;
  std::vector<uint32_t> counts_;
  std::vector<uint32_t> offsets_;
  std::vector<uint32_t> indices_;
};

}  // namespace bounce
