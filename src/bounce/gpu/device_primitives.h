// Scan, sort and reduce on the GPU (CUB, which ships with the CUDA toolkit): the device side of
// core/parallel_primitives.h, with the same results, so count-scan-write passes that are
// deterministic on the CPU stay deterministic here.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bounce/gpu/device_buffer.h"

namespace bounce {

// Temporary memory the primitives reuse from call to call.
struct DeviceScratch {
  DeviceBuffer<unsigned char> temp;
  DeviceBuffer<uint32_t> keys, values;  // the sort's second buffers
  DeviceBuffer<unsigned long long> total;
};

// offsets[0] = 0 and offsets[i + 1] = in[0] + ... + in[i] for i < n (offsets has n + 1 entries
// and must not overlap in). Returns offsets[n], the total, which waits for the GPU.
uint32_t device_exclusive_scan(const uint32_t* in, uint32_t* offsets, size_t n,
                               DeviceScratch& scratch);

// Sorts n (key, value) pairs by the low key_bits bits of the keys, stably (equal keys keep their
// order), in place.
void device_sort_pairs(DeviceBuffer<uint32_t>& keys, DeviceBuffer<uint32_t>& values, size_t n,
                       int key_bits, DeviceScratch& scratch);

// The sum of n values (waits for the GPU).
uint64_t device_sum(const uint32_t* in, size_t n, DeviceScratch& scratch);

}  // namespace bounce
