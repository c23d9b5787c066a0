// The device's scan, sort and sum against the CPU's (core/parallel_primitives.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "bounce/core/parallel_primitives.h"
#include "bounce/core/rng.h"
#include "bounce/gpu/device_primitives.h"
#include "gpu_test_util.h"

namespace bounce {
namespace {

std::vector<uint32_t> random_values(size_t n, uint32_t below, uint32_t seed) {
  Pcg32 rng(seed);
  std::vector<uint32_t> v(n);
  for (uint32_t& x : v) x = rng.next_below(below);
  return v;
}

TEST(DevicePrimitives, ScanEqualsTheCpuScanAndReturnsTheTotal) {
  BOUNCE_REQUIRE_GPU();
  DeviceScratch scratch;
  for (size_t n : {size_t(0), size_t(1), size_t(1000), size_t(1) << 20}) {
    const std::vector<uint32_t> counts = random_values(n, 9, uint32_t(n) + 1);
    std::vector<uint32_t> expected(n + 1, 0);
    expected[n] = exclusive_scan(counts.data(), expected.data(), n);
    DeviceBuffer<uint32_t> in, out(n + 1);
    in.upload(counts);
    const uint32_t total = device_exclusive_scan(in.data(), out.data(), n, scratch);
    EXPECT_EQ(total, expected[n]) << n;
    EXPECT_EQ(out.download(), expected) << n;
  }
}

TEST(DevicePrimitives, SortIsStableByTheLowKeyBits) {
  BOUNCE_REQUIRE_GPU();
  DeviceScratch scratch;
  const size_t n = 300000;
  std::vector<uint32_t> keys = random_values(n, 1000, 7), values(n);
  std::iota(values.begin(), values.end(), 0u);
  DeviceBuffer<uint32_t> k, v;
  k.upload(keys);
  v.upload(values);
  device_sort_pairs(k, v, n, 10, scratch);
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  std::vector<uint32_t> sorted_keys(n);
  for (size_t i = 0; i < n; ++i) sorted_keys[i] = keys[order[i]];
  EXPECT_EQ(k.download(), sorted_keys);
  EXPECT_EQ(v.download(), order);  // stable: equal keys keep their input order
}

TEST(DevicePrimitives, SumDoesNotWrapAt32Bits) {
  BOUNCE_REQUIRE_GPU();
  DeviceScratch scratch;
  const std::vector<uint32_t> big(5000, 4000000000u);
  DeviceBuffer<uint32_t> in;
  in.upload(big);
  EXPECT_EQ(device_sum(in.data(), big.size(), scratch), 5000ull * 4000000000ull);
}

}  // namespace
}  // namespace bounce
