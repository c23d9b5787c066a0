// nvcc check of techniques/tiled/tile_bins_kernels.h: frusta, photon tile ranges and row entries,
// and the per-tile count and insert (the GPU's; the CPU walks rows).
#include "bounce/techniques/tiled/tile_bins_kernels.h"

namespace bounce {

__global__ void check_tile_frusta(ConstGBufferView g, CameraRays camera, TileGrid grid,
                                  TileFrustum* frusta) {
  const size_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < grid.count()) frusta[t] = tile_frustum(g, camera, grid, t);
}

__global__ void check_photon_rows(CameraRays camera, TileGrid grid, const vec3* positions,
                                  uint32_t n, float radius, ivec2* range_x, ivec2* range_y,
                                  const uint32_t* first, uint32_t* rows, uint32_t* photons) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  projected_tile_range(camera, positions[i], radius, grid, range_x[i], range_y[i]);
  if (first)
    write_row_entries(range_y[i], i, first[i], rows, photons);
  else
    rows[i] = photon_row_count(range_y[i]);
}

__global__ void check_row_starts(const uint32_t* sorted_rows, uint32_t entries, uint32_t rows,
                                 uint32_t* starts) {
  const uint32_t r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r <= rows) starts[r] = row_start(sorted_rows, entries, r);
}

__global__ void check_tile_overlaps(TileRowsView rows, const uint32_t* offsets, uint32_t* counts,
                                    uint32_t* indices) {
  const uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= rows.grid.count()) return;
  if (offsets)
    insert_tile_overlaps(rows, t, offsets, indices);
  else
    counts[t] = count_tile_overlaps(rows, t);
}

}  // namespace bounce
