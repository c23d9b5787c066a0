#include "bounce/core/parallel_primitives.h"

#include <algorithm>
#include <array>

#include "bounce/core/error.h"

namespace bounce {

namespace {

constexpr int kRadixBits = 8;
constexpr uint32_t kRadix = 1u << kRadixBits;
constexpr size_t kSortBlock = 16384;

}  // namespace

void sort_by_key(std::span<uint32_t> keys, std::span<uint32_t> values, int key_bits) {
  if (keys.size() != values.size())
    fail("sort_by_key: {} keys but {} values", keys.size(), values.size());
  if (key_bits < 0 || key_bits > 32) fail("sort_by_key: key_bits {} is not in [0, 32]", key_bits);
  const size_t n = keys.size();
  const int passes = (key_bits + kRadixBits - 1) / kRadixBits;
  if (n < 2 || passes == 0) return;

  const size_t blocks = (n + kSortBlock - 1) / kSortBlock;
  std::vector<uint32_t> key_buffer(n), value_buffer(n);
  // offsets[b][d]: where block b's first key with digit d goes; digit-major over blocks, so a
  // scatter that walks each block in order is stable.
  std::vector<std::array<size_t, kRadix>> offsets(blocks);
  uint32_t* key_from = keys.data();
  uint32_t* value_from = values.data();
  uint32_t* key_to = key_buffer.data();
  uint32_t* value_to = value_buffer.data();
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = pass * kRadixBits;
    parallel_for(
        blocks,
        [&](size_t b) {
          std::array<size_t, kRadix>& count = offsets[b];
          count.fill(0);
          const size_t end = std::min(n, (b + 1) * kSortBlock);
          for (size_t i = b * kSortBlock; i < end; ++i)
            ++count[(key_from[i] >> shift) & (kRadix - 1)];
        },
        1);
    size_t running = 0;
    for (uint32_t d = 0; d < kRadix; ++d)
      for (size_t b = 0; b < blocks; ++b) {
        const size_t count = offsets[b][d];
        offsets[b][d] = running;
        running += count;
      }
    parallel_for(
        blocks,
        [&](size_t b) {
          std::array<size_t, kRadix>& next = offsets[b];
          const size_t end = std::min(n, (b + 1) * kSortBlock);
          for (size_t i = b * kSortBlock; i < end; ++i) {
            const size_t slot = next[(key_from[i] >> shift) & (kRadix - 1)]++;
            key_to[slot] = key_from[i];
            value_to[slot] = value_from[i];
          }
        },
        1);
    std::swap(key_from, key_to);
    std::swap(value_from, value_to);
  }
  // After an odd number of passes the result sits in the buffers.
  if (key_from != keys.data()) {
    std::copy(key_from, key_from + n, keys.data());
    std::copy(value_from, value_from + n, values.data());
  }
}

}  // namespace bounce
