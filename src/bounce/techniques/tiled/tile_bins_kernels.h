// Kernel bodies of the screen-tile binning (tile_bins.h) and the plain view the gathers read.
// Binning is count, scan, insert: each photon lists the tile rows its projected bounds cover
// (count per photon, scan, write, stable sort by row); each row walks its photons in order,
// counting then (after a scan over tiles) inserting the ones whose sphere reaches a tile's
// frustum, so every tile's list is in photon order whatever the thread count.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/scene/camera.h"

namespace bounce {

// Screen tiles of tile x tile pixels, tiles_x by tiles_y of them.
struct TileGrid {
  int tile = 8;
  int tiles_x = 0;
  int tiles_y = 0;

  BOUNCE_HD size_t count() const { return size_t(tiles_x) * size_t(tiles_y); }
  BOUNCE_HD size_t tile_of_pixel(int x, int y) const {
    return size_t(y / tile) * size_t(tiles_x) + size_t(x / tile);
  }
};

struct TileFrustum {
  vec3 planes[4];               // unit normals through the eye, pointing out of the tile
  float near_depth, far_depth;  // view depth range of the tile's pixels; empty when near > far
};

// Tile t's depth range and side planes (through the eye and two adjacent tile corners).
BOUNCE_HD inline TileFrustum tile_frustum(const ConstGBufferView& g, const CameraRays& camera,
                                          const TileGrid& grid, size_t t) {
  const int tx = int(t % size_t(grid.tiles_x)), ty = int(t / size_t(grid.tiles_x));
  const int x0 = tx * grid.tile, y0 = ty * grid.tile;
  const int x1 = glm::min(x0 + grid.tile, g.width), y1 = glm::min(y0 + grid.tile, g.height);
  TileFrustum f;
  f.near_depth = std::numeric_limits<float>::infinity();
  f.far_depth = -std::numeric_limits<float>::infinity();
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t i = g.index(x, y);
      if (!g.hit(i)) continue;
      f.near_depth = glm::min(f.near_depth, g.depth[i]);
      f.far_depth = glm::max(f.far_depth, g.depth[i]);
    }
  const vec3 corners[4] = {
      camera.direction(float(x0), float(y0)), camera.direction(float(x1), float(y0)),
      camera.direction(float(x1), float(y1)), camera.direction(float(x0), float(y1))};
  const vec3 inside = camera.direction(0.5f * float(x0 + x1), 0.5f * float(y0 + y1));
  for (int k = 0; k < 4; ++k) {
    const vec3 n = glm::normalize(glm::cross(corners[k], corners[(k + 1) % 4]));
    f.planes[k] = glm::dot(n, inside) > 0.0f ? -n : n;
  }
  return f;
}

// Whether a photon's sphere of influence (p relative to the eye, at view depth `depth`) reaches
// the tile's frustum.
BOUNCE_HD inline bool tile_overlaps(const TileFrustum& f, vec3 p_rel_eye, float depth,
                                    float radius) {
  if (!(depth > f.near_depth - radius && depth < f.far_depth + radius)) return false;
  for (int k = 0; k < 4; ++k)
    if (glm::dot(f.planes[k], p_rel_eye) >= radius) return false;
  return true;
}

// Tile column and row ranges (inclusive; empty when x > y) covered by a sphere's projection: the
// projected corners of its bounding box. A box reaching behind the eye covers the whole screen.
BOUNCE_HD inline void projected_tile_range(const CameraRays& camera, vec3 centre, float radius,
                                           const TileGrid& grid, ivec2& range_x, ivec2& range_y) {
  vec2 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (int c = 0; c < 8; ++c) {
    const vec3 corner = centre + radius * vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
    if (glm::dot(corner - camera.origin, camera.forward) <= 1e-6f) {
      range_x = {0, grid.tiles_x - 1};
      range_y = {0, grid.tiles_y - 1};
      return;
    }
    const vec2 px = camera.project(corner);
    lo = glm::min(lo, px);
    hi = glm::max(hi, px);
  }
  const auto to_tile = [&](float v, int count) {
    return int(glm::clamp(std::floor(v / float(grid.tile)), -1.0f, float(count)));
  };
  range_x = {glm::max(0, to_tile(lo.x, grid.tiles_x)),
             glm::min(grid.tiles_x - 1, to_tile(hi.x, grid.tiles_x))};
  range_y = {glm::max(0, to_tile(lo.y, grid.tiles_y)),
             glm::min(grid.tiles_y - 1, to_tile(hi.y, grid.tiles_y))};
}

// Row entries of photon i: one per tile row it covers.
BOUNCE_HD inline uint32_t photon_row_count(ivec2 range_y) {
  return range_y.y >= range_y.x ? uint32_t(range_y.y - range_y.x + 1) : 0u;
}
// Writes photon i's row entries (row, photon) from slot `first` on.
BOUNCE_HD inline void write_row_entries(ivec2 range_y, uint32_t i, uint32_t first, uint32_t* rows,
                                        uint32_t* photons) {
  for (int ty = range_y.x; ty <= range_y.y; ++ty, ++first) {
    rows[first] = uint32_t(ty);
    photons[first] = i;
  }
}
// First entry of `row` in entries sorted by row (lower bound), so row r's photons are entries
// [row_start(r), row_start(r + 1)).
BOUNCE_HD inline uint32_t row_start(const uint32_t* sorted_rows, uint32_t entries, uint32_t row) {
  uint32_t lo = 0, hi = entries;
  while (lo < hi) {
    const uint32_t mid = (lo + hi) / 2;
    if (sorted_rows[mid] < row)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

// What the row walks read.
struct TileRowsView {
  const TileFrustum* frusta = nullptr;
  const ivec2* photon_tiles_x = nullptr;  // inclusive tile column range of each photon
  const uint32_t* row_start = nullptr;    // tiles_y + 1 offsets into row_photons
  const uint32_t* row_photons = nullptr;  // each row's photons, in photon order
  const vec3* positions = nullptr;        // photon positions
  CameraRays camera;
  float radius = 0.0f;
  TileGrid grid;
};

// Photon i as tile_overlaps tests it: relative to the eye, and at its view depth.
struct PhotonInView {
  vec3 p;
  float depth;
};
BOUNCE_HD inline PhotonInView photon_in_view(const TileRowsView& v, uint32_t i) {
  const vec3 p = v.positions[i] - v.camera.origin;
  return {p, glm::dot(p, v.camera.forward)};
}

// Calls on_overlap(t, i) for every tile t of row ty that photon i's sphere reaches, photons in
// order, tiles left to right.
template <typename OnOverlap>
BOUNCE_HD void for_each_row_overlap(const TileRowsView& v, int ty, OnOverlap&& on_overlap) {
  for (uint32_t r = v.row_start[ty]; r < v.row_start[ty + 1]; ++r) {
    const uint32_t i = v.row_photons[r];
    const PhotonInView q = photon_in_view(v, i);
    for (int tx = v.photon_tiles_x[i].x; tx <= v.photon_tiles_x[i].y; ++tx) {
      const size_t t = size_t(ty) * size_t(v.grid.tiles_x) + size_t(tx);
      if (tile_overlaps(v.frusta[t], q.p, q.depth, v.radius)) on_overlap(t, i);
    }
  }
}

// The same lists one tile at a time, for a GPU thread per tile (a thread per row leaves a
// 1080p frame's 135 rows to 135 threads, serial work of milliseconds): tile t walks its row's
// photons in order and calls on_overlap(i) for those that reach it.
template <typename OnOverlap>
BOUNCE_HD void for_each_tile_overlap(const TileRowsView& v, size_t t, OnOverlap&& on_overlap) {
  const int ty = int(t / size_t(v.grid.tiles_x)), tx = int(t % size_t(v.grid.tiles_x));
  const TileFrustum f = v.frusta[t];
  for (uint32_t r = v.row_start[ty]; r < v.row_start[ty + 1]; ++r) {
    const uint32_t i = v.row_photons[r];
    const ivec2 range = v.photon_tiles_x[i];
    if (tx < range.x || tx > range.y) continue;
    const PhotonInView q = photon_in_view(v, i);
    if (tile_overlaps(f, q.p, q.depth, v.radius)) on_overlap(i);
  }
}
// The number of photons of tile t.
BOUNCE_HD inline uint32_t count_tile_overlaps(const TileRowsView& v, size_t t) {
  uint32_t count = 0;
  for_each_tile_overlap(v, t, [&](uint32_t) { ++count; });
  return count;
}
// Tile t's photons at its offset, in photon order.
BOUNCE_HD inline void insert_tile_overlaps(const TileRowsView& v, size_t t, const uint32_t* offsets,
                                           uint32_t* indices) {
  uint32_t* out = indices + offsets[t];
  for_each_tile_overlap(v, t, [&](uint32_t i) { *out++ = i; });
}

// Count: the number of photons of each tile in row ty (counts zeroed before).
BOUNCE_HD inline void count_row_overlaps(const TileRowsView& v, int ty, uint32_t* counts) {
  for_each_row_overlap(v, ty, [&](size_t t, uint32_t) { ++counts[t]; });
}
// Insert: each tile's photons at its offset (from the scan of the counts), in photon order;
// `fill` (zeroed before) counts what each tile received.
BOUNCE_HD inline void insert_row_overlaps(const TileRowsView& v, int ty, const uint32_t* offsets,
                                          uint32_t* fill, uint32_t* indices) {
  for_each_row_overlap(v, ty, [&](size_t t, uint32_t i) { indices[offsets[t] + fill[t]++] = i; });
}

// The built lists, as the gathers read them.
struct TileBinsView {
  const uint32_t* offsets = nullptr;  // count() + 1
  const uint32_t* indices = nullptr;  // photon indices, tile by tile
  TileGrid grid;

  BOUNCE_HD const uint32_t* begin(size_t t) const { return indices + offsets[t]; }
  BOUNCE_HD const uint32_t* end(size_t t) const { return indices + offsets[t + 1]; }
};
static_assert(std::is_trivially_copyable_v<TileBinsView>);
static_assert(std::is_trivially_copyable_v<TileRowsView>);

}  // namespace bounce
