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

// Forced inlining for bodies that a CPU row loop vectorises: the body must be one basic block
// inside the loop (the denoiser's a-trous pass, direct light's area-light samples).
#if defined(__CUDACC__)
#define BOUNCE_LANE_INLINE __forceinline__
#define BOUNCE_LANE_LAMBDA_INLINE
#elif defined(__GNUC__)
#define BOUNCE_LANE_INLINE __attribute__((always_inline)) inline
#define BOUNCE_LANE_LAMBDA_INLINE __attribute__((always_inline))
#else
#define BOUNCE_LANE_INLINE inline
#define BOUNCE_LANE_LAMBDA_INLINE
#endif

// A loop whose iterations are independent (each writes its own pixel), for GCC's vectoriser.
// Clang warns on GCC's pragma, and its own forcing one warns wherever vectorising fails (the
// sanitizer build), so clang is left to its own analysis.
#if defined(__clang__)
#define BOUNCE_IVDEP
#elif defined(__GNUC__)
#define BOUNCE_IVDEP _Pragma("GCC ivdep")
#else
#define BOUNCE_IVDEP
#endif

namespace bounce {

// T or const T: views come in a writable and a read-only flavour from one definition.
template <typename T, bool kConst>
using maybe_const_t = std::conditional_t<kConst, const T, T>;

}  // namespace bounce
