// DeviceDenoiser (device_denoiser.h) from host data, for tests and tools compiled without CUDA
// headers: uploads a host G-buffer and images, runs the device denoiser, downloads the images.
// Keeps its device denoiser (and so its history) from run to run, as the pipeline does.
#pragma once

#include <memory>

#include "bounce/core/image.h"
#include "bounce/render/denoiser.h"
#include "bounce/render/gbuffer.h"

namespace bounce {

class DeviceDenoiserHost {
 public:
  DeviceDenoiserHost();  // fails in a build without the CUDA backend
  ~DeviceDenoiserHost();
  DeviceDenoiserHost(const DeviceDenoiserHost&) = delete;
  DeviceDenoiserHost& operator=(const DeviceDenoiserHost&) = delete;

  // As Denoiser::run on these inputs: replaces direct (and indirect when not null) in place.
  void run(const DenoiseSettings& settings, const GBuffer& g, HistoryState state,
           IndirectHistory indirect_history, Image& direct, Image* indirect,
           const LightChangeRegion& direct_region = LightChangeRegion::all());

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bounce
