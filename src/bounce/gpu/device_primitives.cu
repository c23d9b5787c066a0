#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>

#include "bounce/gpu/device_primitives.h"

namespace bounce {

namespace {

// CUB's two-call protocol: ask for the temporary size, grow the scratch, run.
template <typename Call>
void run_cub(DeviceScratch& scratch, Call&& call) {
  size_t bytes = 0;
  BOUNCE_CUDA(call(nullptr, bytes));
  scratch.temp.resize(bytes > 0 ? bytes : 1);
  BOUNCE_CUDA(call(scratch.temp.data(), bytes));
}

struct Widen {
  __device__ unsigned long long operator()(uint32_t x) const { return x; }
};
struct Add {
  __device__ unsigned long long operator()(unsigned long long a, unsigned long long b) const {
    return a + b;
  }
};

}  // namespace

uint32_t device_exclusive_scan(const uint32_t* in, uint32_t* offsets, size_t n,
                               DeviceScratch& scratch) {
  BOUNCE_CUDA(cudaMemsetAsync(offsets, 0, sizeof(uint32_t)));
  if (n > 0)
    run_cub(scratch, [&](void* temp, size_t& bytes) {
      return cub::DeviceScan::InclusiveSum(temp, bytes, in, offsets + 1, n);
    });
  uint32_t total = 0;
  BOUNCE_CUDA(cudaMemcpy(&total, offsets + n, sizeof(uint32_t), cudaMemcpyDeviceToHost));
  return total;
}

void device_sort_pairs(DeviceBuffer<uint32_t>& keys, DeviceBuffer<uint32_t>& values, size_t n,
                       int key_bits, DeviceScratch& scratch) {
  if (n < 2) return;
  scratch.keys.resize(n);
  scratch.values.resize(n);
  cub::DoubleBuffer<uint32_t> k(keys.data(), scratch.keys.data());
  cub::DoubleBuffer<uint32_t> v(values.data(), scratch.values.data());
  const int end_bit = key_bits < 1 ? 1 : (key_bits > 32 ? 32 : key_bits);
  run_cub(scratch, [&](void* temp, size_t& bytes) {
    return cub::DeviceRadixSort::SortPairs(temp, bytes, k, v, int(n), 0, end_bit);
  });
  // The sorted run ends in whichever buffer CUB chose: swap it in rather than copy it back.
  if (k.Current() != keys.data()) std::swap(keys, scratch.keys);
  if (v.Current() != values.data()) std::swap(values, scratch.values);
}

uint64_t device_sum(const uint32_t* in, size_t n, DeviceScratch& scratch) {
  if (n == 0) return 0;
  scratch.total.resize(1);
  unsigned long long* out = scratch.total.data();
  // Widened on the fly so that large sums do not wrap.
  run_cub(scratch, [&](void* temp, size_t& bytes) {
    return cub::DeviceReduce::TransformReduce(temp, bytes, in, out, int(n), Add{}, Widen{}, 0ull);
  });
  unsigned long long total = 0;
  BOUNCE_CUDA(cudaMemcpy(&total, out, sizeof(total), cudaMemcpyDeviceToHost));
  return total;
}

}  // namespace bounce
