#include "bounce/techniques/tiled/tile_bins.h"

#include <bit>

#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"

namespace bounce {

void TileBins::build(const GBuffer& g, const CameraRays& camera, const PhotonBuffer& photons,
                     float radius, int tile) {
  grid_ = {tile, (g.width + tile - 1) / tile, (g.height + tile - 1) / tile};
  const size_t tiles = grid_.count();
  const ConstGBufferView gv = g.view();
  frusta_.resize(tiles);
  parallel_for(
      tiles, [&](size_t t) { frusta_[t] = tile_frustum(gv, camera, grid_, t); }, 64);

  // Each photon's tile ranges, then its row entries by count, scan and write.
  const size_t n = photons.size();
  photon_tiles_x_.resize(n);
  photon_tiles_y_.resize(n);
  row_first_.resize(n);
  parallel_for(
      n,
      [&](size_t i) {
        projected_tile_range(camera, photons.position[i], radius, grid_, photon_tiles_x_[i],
                             photon_tiles_y_[i]);
        row_first_[i] = photon_row_count(photon_tiles_y_[i]);
      },
      1024);
  const uint32_t entries = exclusive_scan(row_first_.data(), row_first_.data(), n);
  row_keys_.resize(entries);
  row_photons_.resize(entries);
  parallel_for(
      n,
      [&](size_t i) {
        write_row_entries(photon_tiles_y_[i], uint32_t(i), row_first_[i], row_keys_.data(),
                          row_photons_.data());
      },
      1024);
  // Stable: within a row, photons stay in photon order.
  sort_by_key(row_keys_, row_photons_, std::bit_width(uint32_t(grid_.tiles_y)));
  row_start_.resize(size_t(grid_.tiles_y) + 1);
  parallel_for(
      row_start_.size(),
      [&](size_t r) { row_start_[r] = row_start(row_keys_.data(), entries, uint32_t(r)); }, 64);

  // Rows of tiles are independent: each walks its photons in order, first counting, then (after
  // the scan over tiles) inserting, so every list is in photon order.
  const TileRowsView rows{frusta_.data(),
                          photon_tiles_x_.data(),
                          row_start_.data(),
                          row_photons_.data(),
                          photons.position.data(),
                          camera,
                          radius,
                          grid_};
  counts_.assign(tiles, 0);
  parallel_for(
      size_t(grid_.tiles_y), [&](size_t ty) { count_row_overlaps(rows, int(ty), counts_.data()); },
      1);
  offsets_.resize(tiles + 1);
  offsets_[tiles] = exclusive_scan(counts_.data(), offsets_.data(), tiles);
  indices_.resize(offsets_[tiles]);
  counts_.assign(tiles, 0);
  parallel_for(
      size_t(grid_.tiles_y),
      [&](size_t ty) {
        insert_row_overlaps(rows, int(ty), offsets_.data(), counts_.data(), indices_.data());
      },
      1);
}

}  // namespace bounce
