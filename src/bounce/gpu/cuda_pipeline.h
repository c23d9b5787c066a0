// The CUDA backend's frame pipeline: a DevicePipeline (render/device_pipeline.h) whose stages run
// on the GPU from the same kernel bodies as the CPU's. In a build without nvcc the factory fails
// with a clear message (cuda_unavailable.cpp).
#pragma once

#include <memory>

#include "bounce/render/device_pipeline.h"

namespace bounce {

// Fails unless this build has the backend and a GPU can run it.
std::unique_ptr<DevicePipeline> make_cuda_pipeline();

}  // namespace bounce
