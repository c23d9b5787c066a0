// The CUDA backend's entry points in a build without nvcc: every one says so clearly.
#include "bounce/core/error.h"
#include "bounce/gpu/cuda_device.h"
#include "bounce/gpu/cuda_pipeline.h"
#include "bounce/gpu/device_denoiser_check.h"

namespace bounce {

namespace {
constexpr const char* kNotBuilt =
    "this build of bounce has no CUDA backend (nvcc was not found when it was configured)";
}

const CudaDeviceInfo& cuda_device_info() {
  static const CudaDeviceInfo info = [] {
    CudaDeviceInfo i;
    i.reason = kNotBuilt;
    return i;
  }();
  return info;
}

void require_cuda_device(const std::string& what) {
  fail("{}: {}", what, kNotBuilt);
}

bool cuda_backend_built() {
  return false;
}

std::unique_ptr<DevicePipeline> make_cuda_pipeline() {
  fail("--device cuda: {}", kNotBuilt);
}

struct DeviceDenoiserHost::Impl {};

DeviceDenoiserHost::DeviceDenoiserHost() {
  fail("device denoiser: {}", kNotBuilt);
}
DeviceDenoiserHost::~DeviceDenoiserHost() = default;

void DeviceDenoiserHost::run(const DenoiseSettings&, const GBuffer&, HistoryState, IndirectHistory,
                             Image&, Image*, const LightChangeRegion&) {
  fail("device denoiser: {}", kNotBuilt);
}

}  // namespace bounce
