#include "bounce/render/photon_hash_grid.h"

#include <algorithm>
#include <bit>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"

namespace bounce {

namespace {

constexpr size_t kMinTableSize = 1024;
// Slots, offsets and the skip marker (the table size) are uint32 and the table is >= 2 * count.
constexpr size_t kMaxPoints = size_t(1) << 30;

}  // namespace

void PhotonHashGrid::build(std::span<const vec3> points, float radius) {
  if (!(radius > 0.0f) || !std::isfinite(radius))
    fail("photon hash grid: gather radius must be positive and finite, got {}", radius);
  const float inv_cell = 0.5f / radius;
  if (!std::isfinite(inv_cell))
    fail("photon hash grid: gather radius {} is too small (its cell size is not representable)",
         radius);
  if (points.size() > kMaxPoints)
    fail("photon hash grid: {} points is more than the {} supported", points.size(), kMaxPoints);

  // Cleared first so that a failed allocation below leaves an empty grid, not a stale one.
  cell_start_.clear();
  indices_.clear();
  points_.clear();
  radius_ = radius;
  inv_cell_ = inv_cell;

  const size_t n = points.size();
  const size_t table_size = std::max(kMinTableSize, std::bit_ceil(2 * n));
  const uint32_t no_slot = uint32_t(table_size);  // marks skipped (non-finite) points

  // The view's hash is the query's hash: build and query must compute cells the same way.
  PhotonHashGridView v;
  v.table_mask = uint32_t(table_size - 1);
  v.inv_cell = inv_cell;

  // Slot of every point, in parallel; a pure function of the point, so thread count is moot.
  slots_.resize(n);
  parallel_for(
      n,
      [&](size_t i) {
        const vec3 p = points[i];
        slots_[i] = is_finite(p) ? v.slot(v.cell(p)) : no_slot;
      },
      4096);

  // Counting sort. cell_start[s] first counts slot s, then an inclusive prefix sum turns it into
  // the slot's end; scattering from the last point back, decrementing the end, leaves points in
  // index order within a slot and cell_start[s] at the slot's start.
  cell_start_.assign(table_size + 1, 0);
  uint32_t binned = 0;
  for (size_t i = 0; i < n; ++i) {
    if (slots_[i] == no_slot) continue;
    ++cell_start_[slots_[i]];
    ++binned;
  }
  uint32_t sum = 0;
  for (size_t s = 0; s < table_size; ++s) {
    sum += cell_start_[s];
    cell_start_[s] = sum;
  }
  cell_start_[table_size] = binned;
  indices_.resize(binned);
  for (size_t i = n; i-- > 0;) {
    if (slots_[i] == no_slot) continue;
    indices_[--cell_start_[slots_[i]]] = uint32_t(i);
  }

  // Positions in sorted order so a gather reads one contiguous run per slot.
  points_.resize(binned);
  parallel_for(
      binned, [&](size_t k) { points_[k] = points[indices_[k]]; }, 4096);
}

}  // namespace bounce
