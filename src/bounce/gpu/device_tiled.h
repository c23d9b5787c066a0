// Technique `tiled` on the GPU: the same frame as techniques/tiled/tiled.cpp (photons traced in
// prepare, clearance rays, screen-tile bins or the hash grid, the low-resolution cone-filter
// gather with edge re-estimation, progressive passes at rest) from the same kernel bodies, with
// the settings read from the host technique's parameters.
//
// Deviation (issue 13 notes): passes are averaged while nothing changes, as on the CPU, and the
// frames after a restart trace restart_passes passes each, as on the CPU; but the kept passes
// that the CPU gathers again after a camera move are not kept here yet: a camera move restarts
// the average at the full radius (without the boost, which the CPU gives restarts of the world).
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/gpu/device_buffer.h"
#include "bounce/gpu/device_photons.h"
#include "bounce/render/technique.h"
#include "bounce/techniques/tiled/tiled.h"

namespace bounce {

class DeviceScene;

class DeviceTiled {
 public:
  // Traces the frame's photon pass (and its clearances).
  void prepare(const TiledSettings& settings, const DeviceScene& scene, const SceneChange& change,
               bool accumulate, uint32_t frame_index, TechniqueCounters& counters);
  // Indirect radiance of every pixel into out (width x height, device memory).
  void indirect(const DeviceScene& scene, const ConstGBufferView& g, const CameraRays& camera,
                vec3* out);
  uint32_t passes() const { return passes_; }

 private:
  TiledSettings settings_;
  float diagonal_ = 1.0f, full_radius_ = 0.0f;
  uint32_t passes_ = 0;
  uint32_t frame_passes_ = 1;  // traced by this frame's prepare (TiledPhotonMapping's)
  RestartBoost boost_;
  DevicePhotons photons_;             // this frame's passes, gathered together
  std::vector<DevicePhotons> parts_;  // a boosted frame's passes, before they are joined
  DevicePhotonTracer tracer_;
  DeviceTileBins bins_;
  DeviceHashGrid grid_;
  DeviceBuffer<vec3> pass_, sum_, low_radiance_, low_normal_, low_position_;
  DeviceBuffer<uint8_t> low_valid_;
};

}  // namespace bounce
