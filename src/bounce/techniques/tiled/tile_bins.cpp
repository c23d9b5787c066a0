#include "bounce/techniques/tiled/tile_bins.h"

#include <limits>

#include "bounce/core/parallel.h"

namespace bounce {

namespace {

// Tile column and row ranges covered by a sphere's projection: the projected corners of its
// bounding box. A box reaching behind the eye covers the whole screen.
void projected_tile_range(const CameraRays& camera, vec3 centre, float radius, int tile,
                          int tiles_x, int tiles_y, ivec2& range_x, ivec2& range_y) {
  vec2 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (int c = 0; c < 8; ++c) {
    const vec3 corner = centre + radius * vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
    if (glm::dot(corner - camera.origin, camera.forward) <= 1e-6f) {
      range_x = {0, tiles_x - 1};
      range_y = {0, tiles_y - 1};
      return;
    }
    const vec2 px = camera.project(corner);
    lo = glm::min(lo, px);
    hi = glm::max(hi, px);
  }
  const auto to_tile = [&](float v, int count) {
    return int(glm::clamp(std::floor(v / float(tile)), -1.0f, float(count)));
  };
  range_x = {std::max(0, to_tile(lo.x, tiles_x)), std::min(tiles_x - 1, to_tile(hi.x, tiles_x))};
  range_y = {std::max(0, to_tile(lo.y, tiles_y)), std::min(tiles_y - 1, to_tile(hi.y, tiles_y))};
}

}  // namespace

bool TileBins::overlaps(const TileFrustum& f, vec3 p, float depth, float radius) const {
  if (!(depth > f.near_depth - radius && depth < f.far_depth + radius)) return false;
  for (const vec3& plane : f.planes)
    if (glm::dot(plane, p) >= radius) return false;
  return true;
}

void TileBins::build(const GBuffer& g, const CameraRays& camera, const PhotonBuffer& photons,
                     float radius, int tile) {
  tile_ = tile;
  tiles_x_ = (g.width + tile - 1) / tile;
  tiles_y_ = (g.height + tile - 1) / tile;
  const size_t tiles = size_t(tiles_x_) * tiles_y_;
  frusta_.resize(tiles);

  // Each tile's depth range and side planes (through the eye and two adjacent tile corners).
  parallel_for(
      tiles,
      [&](size_t t) {
        const int tx = int(t % tiles_x_), ty = int(t / tiles_x_);
        const int x0 = tx * tile, y0 = ty * tile;
        const int x1 = std::min(x0 + tile, g.width), y1 = std::min(y0 + tile, g.height);
        TileFrustum& f = frusta_[t];
        f.near_depth = std::numeric_limits<float>::infinity();
        f.far_depth = -std::numeric_limits<float>::infinity();
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) {
            const size_t i = size_t(y) * g.width + x;
            if (!g.hit(i)) continue;
            f.near_depth = std::min(f.near_depth, g.depth[i]);
            f.far_depth = std::max(f.far_depth, g.depth[i]);
          }
        const vec3 corners[4] = {
            camera.direction(float(x0), float(y0)), camera.direction(float(x1), float(y0)),
            camera.direction(float(x1), float(y1)), camera.direction(float(x0), float(y1))};
        const vec3 inside = camera.direction(0.5f * (x0 + x1), 0.5f * (y0 + y1));
        for (int k = 0; k < 4; ++k) {
          vec3 n = glm::normalize(glm::cross(corners[k], corners[(k + 1) % 4]));
          f.planes[k] = glm::dot(n, inside) > 0.0f ? -n : n;
        }
      },
      64);

  const size_t n = photons.size();
  photon_tiles_x_.resize(n);
  photon_tiles_y_.resize(n);
  parallel_for(
      n,
      [&](size_t i) {
        projected_tile_range(camera, photons.position[i], radius, tile, tiles_x_, tiles_y_,
                             photon_tiles_x_[i], photon_tiles_y_[i]);
      },
      1024);

  // Each photon is listed under the tile rows its bounds cover (counting sort, photon order
  // within a row), so a row visits only its own photons.
  row_start_.assign(size_t(tiles_y_) + 1, 0);
  for (size_t i = 0; i < n; ++i)
    for (int ty = photon_tiles_y_[i].x; ty <= photon_tiles_y_[i].y; ++ty) ++row_start_[ty + 1];
  for (int ty = 0; ty < tiles_y_; ++ty) row_start_[ty + 1] += row_start_[ty];
  row_photons_.resize(row_start_[tiles_y_]);
  {
    std::vector<uint32_t> cursor(row_start_.begin(), row_start_.end() - 1);
    for (size_t i = 0; i < n; ++i)
      for (int ty = photon_tiles_y_[i].x; ty <= photon_tiles_y_[i].y; ++ty)
        row_photons_[cursor[ty]++] = uint32_t(i);
  }

  // Rows of tiles are independent: each walks its photons in order, first counting, then (after
  // the prefix sum) inserting, so every list is in photon order.
  counts_.assign(tiles, 0);
  const auto walk_row = [&](int ty, auto&& on_overlap) {
    for (uint32_t r = row_start_[ty]; r < row_start_[ty + 1]; ++r) {
      const uint32_t i = row_photons_[r];
      const vec3 p = photons.position[i] - camera.origin;
      const float depth = glm::dot(p, camera.forward);
      for (int tx = photon_tiles_x_[i].x; tx <= photon_tiles_x_[i].y; ++tx) {
        const size_t t = size_t(ty) * tiles_x_ + tx;
        if (overlaps(frusta_[t], p, depth, radius)) on_overlap(t, i);
      }
    }
  };
  parallel_for(
      size_t(tiles_y_),
      [&](size_t ty) { walk_row(int(ty), [&](size_t t, uint32_t) { ++counts_[t]; }); }, 1);
  offsets_.resize(tiles + 1);
  offsets_[0] = 0;
  for (size_t t = 0; t < tiles; ++t) offsets_[t + 1] = offsets_[t] + counts_[t];
  indices_.resize(offsets_[tiles]);
  parallel_for(
      size_t(tiles_y_),
      [&](size_t ty) {
        walk_row(int(ty), [&](size_t t, uint32_t i) { indices_[offsets_[t]++] = i; });
      },
      1);
  // The insert pass advanced each offset to its tile's end; shift back to the starts.
  for (size_t t = tiles; t > 0; --t) offsets_[t] = offsets_[t - 1];
  offsets_[0] = 0;
}

}  // namespace bounce
