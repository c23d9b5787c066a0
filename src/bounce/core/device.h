// Host/device annotations for kernel code. Per-pixel, per-photon and per-triangle bodies are
// plain functions marked BOUNCE_HD: ordinary inline functions for the C++ compiler, and
// __host__ __device__ functions when nvcc compiles them, so one source serves both backends.
#pragma once

#include <type_traits>

#if defined(__CUDACC__)
#define BOUNCE_HD __host__ __device__
#else
#define BOUNCE_HD
#endif

// 1 while nvcc compiles the device side of a translation unit, 0 on every host pass. Code that
// can only run on one side (Embree on the host, our own BVH on the device) branches on it.
#if defined(__CUDA_ARCH__)
#define BOUNCE_DEVICE_CODE 1
#else
#define BOUNCE_DEVICE_CODE 0
#endif

namespace bounce {

// T or const T: views come in a writable and a read-only flavour from one definition.
template <typename T, bool kConst>
using maybe_const_t = std::conditional_t<kConst, const T, T>;

}  // namespace bounce
