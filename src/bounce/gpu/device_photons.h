// Photons on the GPU: tracing a pass (count, scan, write: the CPU's deterministic slots), their
// clearance rays, and the two indexes the tiled gather reads (screen-tile bins and the hash grid),
// each from the same kernel bodies as the CPU's (render/photon_path.h, photon_clearance.h,
// techniques/tiled/tile_bins_kernels.h, render/photon_hash_grid.h).
#pragma once

#include <cstdint>
#include <span>

#include "bounce/gpu/device_buffer.h"
#include "bounce/gpu/device_primitives.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/photon_hash_grid.h"
#include "bounce/render/photon_path.h"
#include "bounce/render/photon_tracing.h"
#include "bounce/render/photon_view.h"
#include "bounce/scene/camera.h"
#include "bounce/techniques/tiled/tile_bins_kernels.h"

namespace bounce {

class DeviceScene;

struct DevicePhotons {
  DeviceBuffer<vec3> position, flux, incident_dir, normal_dir;
  DeviceBuffer<uint32_t> incident, normal;
  DeviceBuffer<float> clearance, min_clearance;
  uint32_t count = 0;
  bool has_clearance = false;

  // Room for n photons (contents not kept when it grows), with no clearances yet.
  void resize(uint32_t n);
  PhotonView view();
};

// The photons of `parts` one after another in `out` (without clearances: they are per photon, so
// the joined photons' are computed after).
void join_photons(std::span<const DevicePhotons> parts, DevicePhotons& out);

struct DevicePhotonStats {
  uint64_t paths = 0, stored = 0, rays = 0;
};

class DevicePhotonTracer {
 public:
  DevicePhotonStats trace(const DeviceScene& scene, const PhotonTraceSettings& settings,
                          DevicePhotons& out);
  // Clearance rays out to `radius` for every photon (kClearanceRays each); returns the rays.
  uint64_t clearance(const DeviceScene& scene, float radius, DevicePhotons& photons);

 private:
  DeviceBuffer<uint32_t> counts_, first_, rays_;
  DeviceScratch scratch_;
};

// Screen-tile bins (techniques/tiled/tile_bins.h), built on the device.
class DeviceTileBins {
 public:
  void build(const ConstGBufferView& g, const CameraRays& camera, const DevicePhotons& photons,
             float radius, int tile);
  TileBinsView view() const { return {offsets_.data(), indices_.data(), grid_}; }

 private:
  TileGrid grid_;
  DeviceBuffer<TileFrustum> frusta_;
  DeviceBuffer<ivec2> tiles_x_, tiles_y_;
  DeviceBuffer<uint32_t> row_counts_, row_first_, row_keys_, row_photons_, row_start_;
  DeviceBuffer<uint32_t> counts_, offsets_, indices_;
  DeviceScratch scratch_;
};

// The photon hash grid (render/photon_hash_grid.h), built on the device: a stable sort by slot
// gives the CPU's counting sort's order exactly.
class DeviceHashGrid {
 public:
  void build(const DevicePhotons& photons, float radius);
  PhotonHashGridView view() const { return view_; }

 private:
  PhotonHashGridView view_;
  DeviceBuffer<uint32_t> slots_, indices_, cell_start_;
  DeviceBuffer<vec3> points_;
  DeviceScratch scratch_;
};

}  // namespace bounce
