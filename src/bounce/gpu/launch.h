// The CUDA side of parallel_for: launches a kernel body (a device lambda or functor taken by
// value) once per index or per pixel. Bodies are the same free functions the CPU runs through
// core/parallel.h; only the capture differs (by value here, since the GPU cannot see the host's
// stack).
#pragma once

#include <cstddef>
#include <cstdint>

#include "bounce/gpu/cuda_check.h"

namespace bounce {

namespace detail {

template <typename Body>
__global__ void launch_1d_kernel(uint32_t n, Body body) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) body(i);
}

template <typename Body>
__global__ void launch_2d_kernel(int width, int height, Body body) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (x < width && y < height) body(x, y);
}

}  // namespace detail

// body(i) for every i in [0, n), asynchronously on the default stream.
template <typename Body>
void launch(size_t n, Body body, int block = 128) {
  if (n == 0) return;
  const uint32_t blocks = uint32_t((n + size_t(block) - 1) / size_t(block));
  detail::launch_1d_kernel<<<blocks, block>>>(uint32_t(n), body);
  BOUNCE_CUDA(cudaGetLastError());
}

// body(x, y) for every pixel of a width x height grid, in 8 x 8 blocks (the CPU's tiles).
template <typename Body>
void launch_2d(int width, int height, Body body) {
  if (width <= 0 || height <= 0) return;
  const dim3 block(8, 8);
  const dim3 grid((unsigned(width) + 7) / 8, (unsigned(height) + 7) / 8);
  detail::launch_2d_kernel<<<grid, block>>>(width, height, body);
  BOUNCE_CUDA(cudaGetLastError());
}

}  // namespace bounce
