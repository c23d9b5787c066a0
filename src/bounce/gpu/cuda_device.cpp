#include "bounce/gpu/cuda_device.h"

#include <fmt/format.h>

#include "bounce/core/error.h"
#include "bounce/gpu/cuda_check.h"

namespace bounce {

void gpu_fail(const std::string& message) {
  fail("{}", message);
}

void cuda_check(cudaError_t status, const char* call, const char* file, int line) {
  if (status == cudaSuccess) return;
  fail("CUDA: {} failed: {} ({}:{})", call, cudaGetErrorString(status), file, line);
}

const CudaDeviceInfo& cuda_device_info() {
  static const CudaDeviceInfo info = [] {
    CudaDeviceInfo i;
    int count = 0;
    const cudaError_t status = cudaGetDeviceCount(&count);
    if (status != cudaSuccess) {
      // No driver, or a driver older than this build's runtime: both read as "no GPU here".
      i.reason = fmt::format("no usable CUDA GPU ({})", cudaGetErrorString(status));
      cudaGetLastError();  // clears the sticky error for later calls
      return i;
    }
    if (count == 0) {
      i.reason = "no CUDA GPU found";
      return i;
    }
    cudaDeviceProp prop{};
    if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) {
      i.reason = "the CUDA runtime could not read GPU 0's properties";
      return i;
    }
    i.available = true;
    i.name = prop.name;
    i.compute_major = prop.major;
    i.compute_minor = prop.minor;
    i.multiprocessors = prop.multiProcessorCount;
    i.memory_bytes = prop.totalGlobalMem;
    return i;
  }();
  return info;
}

void require_cuda_device(const std::string& what) {
  const CudaDeviceInfo& info = cuda_device_info();
  if (!info.available) fail("{}: {}", what, info.reason);
}

bool cuda_backend_built() {
  return true;
}

}  // namespace bounce
