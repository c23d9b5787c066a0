// The parallel primitives kernels are built from, besides parallel_for: exclusive scan, reduce
// and a stable sort by key. Each result depends only on the input, never on the thread count:
// work is cut into blocks of a fixed size (not one per thread) and block results are combined in
// block order, so even floating-point sums come out bit for bit the same. A CUDA backend
// provides the same three with the same contracts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bounce/core/parallel.h"

namespace bounce {

// Elements per block of the scan and the reduce: large enough to amortise a task, small enough
// to spread a frame's worth of work (tens of thousands of items) over the cores.
inline constexpr size_t kScanBlock = 8192;

// Exclusive prefix sum: out[i] = in[0] + ... + in[i - 1] (out[0] = 0). Returns the total. `in`
// and `out` may be the same array.
template <typename T>
T exclusive_scan(const T* in, T* out, size_t n) {
  const size_t blocks = (n + kScanBlock - 1) / kScanBlock;
  std::vector<T> block_start(blocks, T(0));
  // Block sums, then their own scan (a handful of values), then each block scanned from its start.
  parallel_for(
      blocks,
      [&](size_t b) {
        const size_t end = std::min(n, (b + 1) * kScanBlock);
        T sum = T(0);
        for (size_t i = b * kScanBlock; i < end; ++i) sum += in[i];
        block_start[b] = sum;
      },
      1);
  T total = T(0);
  for (size_t b = 0; b < blocks; ++b) {
    const T sum = block_start[b];
    block_start[b] = total;
    total += sum;
  }
  parallel_for(
      blocks,
      [&](size_t b) {
        const size_t end = std::min(n, (b + 1) * kScanBlock);
        T running = block_start[b];
        for (size_t i = b * kScanBlock; i < end; ++i) {
          const T value = in[i];
          out[i] = running;
          running += value;
        }
      },
      1);
  return total;
}

// In place over a vector.
template <typename T>
T exclusive_scan(std::vector<T>& values) {
  return exclusive_scan(values.data(), values.data(), values.size());
}

// combine(...combine(combine(identity, map(0)), map(1))..., map(n - 1)), evaluated in blocks of
// `block` items (results combined in block order): `combine` must be associative (and `identity`
// its identity) for that to be the same value. A small block suits expensive items (a row of
// pixels); the result depends on the block size, never on the threads.
template <typename T, typename Map, typename Combine>
T parallel_reduce(size_t n, T identity, Map&& map, Combine&& combine, size_t block = kScanBlock) {
  const size_t blocks = (n + block - 1) / block;
  std::vector<T> partial(blocks, identity);
  parallel_for(
      blocks,
      [&](size_t b) {
        const size_t end = std::min(n, (b + 1) * block);
        T value = identity;
        for (size_t i = b * block; i < end; ++i) value = combine(value, map(i));
        partial[b] = value;
      },
      1);
  T result = identity;
  for (const T& value : partial) result = combine(result, value);
  return result;
}

// Sorts `keys` ascending and permutes `values` (same length) along with them. Stable: equal keys
// keep their input order. A least-significant-digit radix sort, 8 bits a pass, as many passes as
// `key_bits` needs (keys must be below 2^key_bits).
void sort_by_key(std::span<uint32_t> keys, std::span<uint32_t> values, int key_bits = 32);

}  // namespace bounce
