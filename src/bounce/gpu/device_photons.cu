#include <algorithm>
#include <bit>
#include <string>

#include "bounce/core/octahedral.h"
#include "bounce/gpu/device_photons.h"
#include "bounce/gpu/device_scene.h"
#include "bounce/gpu/launch.h"
#include "bounce/render/photon_clearance.h"

namespace bounce {

PhotonView DevicePhotons::view() {
  PhotonView v;
  v.position = position.data();
  v.flux = flux.data();
  v.incident = incident.data();
  v.normal = normal.data();
  v.clearance = has_clearance ? clearance.data() : nullptr;
  v.min_clearance = has_clearance ? min_clearance.data() : nullptr;
  v.incident_dir = incident_dir.data();
  v.normal_dir = normal_dir.data();
  v.count = count;
  return v;
}

void DevicePhotons::resize(uint32_t n) {
  position.resize(n);
  flux.resize(n);
  incident.resize(n);
  normal.resize(n);
  incident_dir.resize(n);
  normal_dir.resize(n);
  count = n;
  has_clearance = false;
}

void join_photons(std::span<const DevicePhotons> parts, DevicePhotons& out) {
  uint32_t total = 0;
  for (const DevicePhotons& p : parts) total += p.count;
  out.resize(total);
  uint32_t at = 0;
  const auto copy = [](auto& to, const auto& from, uint32_t offset, uint32_t n) {
    if (n)
      BOUNCE_CUDA(cudaMemcpyAsync(to.data() + offset, from.data(), n * sizeof(*from.data()),
                                  cudaMemcpyDeviceToDevice));
  };
  for (const DevicePhotons& p : parts) {
    copy(out.position, p.position, at, p.count);
    copy(out.flux, p.flux, at, p.count);
    copy(out.incident, p.incident, at, p.count);
    copy(out.normal, p.normal, at, p.count);
    copy(out.incident_dir, p.incident_dir, at, p.count);
    copy(out.normal_dir, p.normal_dir, at, p.count);
    at += p.count;
  }
}

DevicePhotonStats DevicePhotonTracer::trace(const DeviceScene& scene,
                                            const PhotonTraceSettings& settings,
                                            DevicePhotons& out) {
  DevicePhotonStats stats;
  out.count = 0;
  out.has_clearance = false;
  const PhotonPass pass = photon_pass(settings);
  if (!scene.has_emitters() || pass.paths == 0) return stats;
  stats.paths = pass.paths;
  const SceneView sv = scene.view();
  const TraceView tv = scene.trace();
  const PhotonEmitterView ev = scene.emitters();
  // Count each path's photons, scan to slots, trace again writing them: the same slots as the
  // CPU's, so the photon map does not depend on the order threads run in.
  counts_.resize(pass.paths);
  rays_.resize(pass.paths);
  first_.resize(size_t(pass.paths) + 1);
  uint32_t* counts = counts_.data();
  uint32_t* rays = rays_.data();
  launch(pass.paths, [=] __device__(uint32_t i) {
    counts[i] = trace_photon_path(
        sv, tv, ev, pass, i, [](uint32_t, const PhotonDeposit&) {}, rays[i]);
  });
  const uint32_t total = device_exclusive_scan(counts, first_.data(), pass.paths, scratch_);
  stats.rays = 2 * device_sum(rays, pass.paths, scratch_);  // each path is traced twice
  out.resize(total);
  const PhotonView pv = out.view();
  const uint32_t* first = first_.data();
  launch(pass.paths, [=] __device__(uint32_t i) {
    uint32_t r;
    trace_photon_path(
        sv, tv, ev, pass, i,
        [&](uint32_t k, const PhotonDeposit& d) { store_photon(pv, first[i] + k, d); }, r);
  });
  launch(total, [=] __device__(uint32_t i) {
    pv.incident_dir[i] = oct_unpack(pv.incident[i]);
    pv.normal_dir[i] = oct_unpack(pv.normal[i]);
  });
  stats.stored = total;
  return stats;
}

uint64_t DevicePhotonTracer::clearance(const DeviceScene& scene, float radius,
                                       DevicePhotons& photons) {
  photons.clearance.resize(size_t(photons.count) * kClearanceRays);
  photons.min_clearance.resize(photons.count);
  photons.has_clearance = true;
  const PhotonView pv = photons.view();
  const TraceView tv = scene.trace();
  launch(photons.count, [=] __device__(uint32_t i) { photon_clearance(tv, pv, i, radius); });
  return uint64_t(photons.count) * kClearanceRays;
}

void DeviceTileBins::build(const ConstGBufferView& g, const CameraRays& camera,
                           const DevicePhotons& photons, float radius, int tile) {
  grid_ = {tile, (g.width + tile - 1) / tile, (g.height + tile - 1) / tile};
  const TileGrid grid = grid_;
  const size_t tiles = grid.count();
  frusta_.resize(tiles);
  TileFrustum* frusta = frusta_.data();
  launch(tiles, [=] __device__(uint32_t t) { frusta[t] = tile_frustum(g, camera, grid, t); });
  // Each photon's tile ranges and row entries: count, scan, write, stable sort by row.
  const uint32_t n = photons.count;
  tiles_x_.resize(n);
  tiles_y_.resize(n);
  row_counts_.resize(n);
  row_first_.resize(size_t(n) + 1);
  ivec2* tx = tiles_x_.data();
  ivec2* ty = tiles_y_.data();
  uint32_t* row_counts = row_counts_.data();
  const vec3* positions = photons.position.data();
  launch(n, [=] __device__(uint32_t i) {
    projected_tile_range(camera, positions[i], radius, grid, tx[i], ty[i]);
    row_counts[i] = photon_row_count(ty[i]);
  });
  const uint32_t entries = device_exclusive_scan(row_counts, row_first_.data(), n, scratch_);
  row_keys_.resize(entries);
  row_photons_.resize(entries);
  {
    const uint32_t* row_first = row_first_.data();
    uint32_t* keys = row_keys_.data();
    uint32_t* values = row_photons_.data();
    launch(n,
           [=] __device__(uint32_t i) { write_row_entries(ty[i], i, row_first[i], keys, values); });
  }
  device_sort_pairs(row_keys_, row_photons_, entries, std::bit_width(uint32_t(grid.tiles_y)),
                    scratch_);
  row_start_.resize(size_t(grid.tiles_y) + 1);
  {
    const uint32_t* keys = row_keys_.data();
    uint32_t* starts = row_start_.data();
    launch(size_t(grid.tiles_y) + 1,
           [=] __device__(uint32_t r) { starts[r] = row_start(keys, entries, r); });
  }
  const TileRowsView rows{
      frusta_.data(), tx, row_start_.data(), row_photons_.data(), positions, camera, radius, grid};
  // One thread per tile walks its row's photons in order: count, scan over tiles, insert.
  counts_.resize(tiles);
  uint32_t* counts = counts_.data();
  launch(tiles, [=] __device__(uint32_t t) { counts[t] = count_tile_overlaps(rows, t); });
  offsets_.resize(tiles + 1);
  const uint32_t total = device_exclusive_scan(counts, offsets_.data(), tiles, scratch_);
  indices_.resize(total);
  const uint32_t* offsets = offsets_.data();
  uint32_t* indices = indices_.data();
  launch(tiles, [=] __device__(uint32_t t) { insert_tile_overlaps(rows, t, offsets, indices); });
}

void DeviceHashGrid::build(const DevicePhotons& photons, float radius) {
  if (!(radius > 0.0f) || !std::isfinite(radius))
    gpu_fail("photon hash grid: gather radius must be positive and finite, got " +
             std::to_string(radius));
  const uint32_t n = photons.count;
  const size_t table_size = std::max<size_t>(1024, std::bit_ceil(2 * size_t(n)));
  const uint32_t no_slot = uint32_t(table_size);
  PhotonHashGridView v;
  v.table_mask = uint32_t(table_size - 1);
  v.inv_cell = 0.5f / radius;
  v.radius = radius;
  slots_.resize(n);
  indices_.resize(n);
  const vec3* positions = photons.position.data();
  uint32_t* slots = slots_.data();
  uint32_t* indices = indices_.data();
  launch(n, [=] __device__(uint32_t i) {
    const vec3 p = positions[i];
    slots[i] = is_finite(p) ? v.slot(v.cell(p)) : no_slot;
    indices[i] = i;
  });
  // Stable: within a slot, points stay in index order, as the CPU's counting sort leaves them.
  // Skipped points (slot == table size) sort last.
  device_sort_pairs(slots_, indices_, n, std::bit_width(uint32_t(table_size)), scratch_);
  cell_start_.resize(table_size + 1);
  slots = slots_.data();
  indices = indices_.data();
  uint32_t* starts = cell_start_.data();
  launch(table_size + 1, [=] __device__(uint32_t s) { starts[s] = row_start(slots, n, s); });
  // Binned points: those before the first skipped one, i.e. cell_start[table_size].
  uint32_t binned = 0;
  BOUNCE_CUDA(cudaMemcpy(&binned, starts + table_size, sizeof(uint32_t), cudaMemcpyDeviceToHost));
  points_.resize(binned);
  vec3* points = points_.data();
  launch(binned, [=] __device__(uint32_t k) { points[k] = positions[indices[k]]; });
  v.cell_start = starts;
  v.index = indices;
  v.point = points;
  v.count = binned;
  view_ = v;
}

}  // namespace bounce
