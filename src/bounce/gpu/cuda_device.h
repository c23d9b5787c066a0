// Whether this process can run the CUDA backend, and why not. Plain C++ (no CUDA headers), so the
// command line and the tests can ask before they build anything; in a build without nvcc the
// answer is always "no" with the reason.
#pragma once

#include <cstddef>
#include <string>

namespace bounce {

struct CudaDeviceInfo {
  bool available = false;
  std::string reason;  // why not, when not available
  std::string name;    // the GPU, e.g. "NVIDIA H100 80GB HBM3"
  int compute_major = 0, compute_minor = 0;
  int multiprocessors = 0;
  size_t memory_bytes = 0;
};

// Device 0 as the CUDA runtime sees it; asked once, then remembered.
const CudaDeviceInfo& cuda_device_info();

// Fails with a message naming `what` (e.g. "--device cuda") and the reason when no GPU can run
// the backend.
void require_cuda_device(const std::string& what);

// True when this build contains the CUDA backend (nvcc was found when it was configured).
bool cuda_backend_built();

}  // namespace bounce
