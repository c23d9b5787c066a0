// CUDA runtime errors as bounce errors: every runtime call goes through cuda_check, which fails
// with the call's text and CUDA's own message instead of carrying on with a broken device.
#pragma once

#include <cuda_runtime.h>

#include <string>

namespace bounce {

// Throws bounce's Error with `message`. CUDA files call this instead of fail(): nvcc cannot
// compile fmt's compile-time format checks, so the formatting lives in a C++ file.
[[noreturn]] void gpu_fail(const std::string& message);

void cuda_check(cudaError_t status, const char* call, const char* file, int line);

}  // namespace bounce

#define BOUNCE_CUDA(call) ::bounce::cuda_check((call), #call, __FILE__, __LINE__)
