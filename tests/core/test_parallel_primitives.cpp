#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"
#include "bounce/core/rng.h"

namespace bounce {
namespace {

// Sizes around the block boundaries and one spanning many blocks.
const size_t kSizes[] = {0, 1, 7, kScanBlock - 1, kScanBlock, kScanBlock + 1, 100003};

std::vector<uint32_t> random_values(size_t n, uint32_t bound, uint32_t seed) {
  Pcg32 rng(seed);
  std::vector<uint32_t> v(n);
  for (auto& x : v) x = rng.next_below(bound);
  return v;
}

TEST(ParallelFor2D, VisitsEveryPixelOnce) {
  for (const ivec2 size : {ivec2(0, 0), ivec2(1, 1), ivec2(13, 7), ivec2(100, 37), ivec2(3, 0)}) {
    std::vector<int> visits(size_t(size.x) * size.y, 0);
    parallel_for_2d(size.x, size.y, [&](int x, int y) {
      ASSERT_TRUE(x >= 0 && x < size.x && y >= 0 && y < size.y);
      ++visits[size_t(y) * size.x + x];  // each pixel by one task only, so no race
    });
    for (int v : visits) EXPECT_EQ(v, 1) << size.x << "x" << size.y;
  }
}

TEST(ParallelForTiles, CoverEveryPixelOnceInTilesOfTheGivenShape) {
  for (const ivec2 size : {ivec2(0, 0), ivec2(1, 1), ivec2(13, 7), ivec2(100, 37), ivec2(3, 0)})
    for (const ivec2 tile : {ivec2(8, 8), ivec2(64, 1), ivec2(5, 3)}) {
      std::vector<int> visits(size_t(size.x) * size.y, 0);
      parallel_for_tiles(size.x, size.y, tile.x, tile.y, [&](int x0, int y0, int x1, int y1) {
        // A tile starts on the grid and is clipped only by the image's edges.
        EXPECT_EQ(x0 % tile.x, 0);
        EXPECT_EQ(y0 % tile.y, 0);
        EXPECT_EQ(x1, std::min(x0 + tile.x, size.x));
        EXPECT_EQ(y1, std::min(y0 + tile.y, size.y));
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) ++visits[size_t(y) * size.x + x];  // one task a pixel
      });
      for (int v : visits)
        EXPECT_EQ(v, 1) << size.x << "x" << size.y << " in " << tile.x << "x" << tile.y;
    }
}

TEST(ExclusiveScan, MatchesASerialPrefixSumInAndOutOfPlace) {
  for (size_t n : kSizes) {
    const std::vector<uint32_t> in = random_values(n, 50, uint32_t(n) + 1);
    std::vector<uint32_t> expected(n);
    uint32_t sum = 0;
    for (size_t i = 0; i < n; ++i) {
      expected[i] = sum;
      sum += in[i];
    }
    std::vector<uint32_t> out(n, 12345);
    EXPECT_EQ(exclusive_scan(in.data(), out.data(), n), sum) << n;
    EXPECT_EQ(out, expected) << n;
    std::vector<uint32_t> in_place = in;
    EXPECT_EQ(exclusive_scan(in_place), sum) << n;
    EXPECT_EQ(in_place, expected) << n;
  }
}

TEST(ExclusiveScan, FloatSumsAreTheSameWithOneOrTwoThreads) {
  Pcg32 rng(3);
  std::vector<float> in(3 * kScanBlock + 17);
  for (float& x : in) x = rng.next_float() * 1000.0f;
  std::vector<float> one(in.size()), two(in.size());
  float total_one, total_two;
  {
    ThreadLimit limit(1);
    total_one = exclusive_scan(in.data(), one.data(), in.size());
  }
  {
    ThreadLimit limit(2);
    total_two = exclusive_scan(in.data(), two.data(), in.size());
  }
  EXPECT_EQ(total_one, total_two);
  EXPECT_EQ(one, two);
  // And it is a prefix sum: within float rounding of the double one.
  double running = 0.0;
  for (size_t i = 0; i < in.size(); i += 997) {
    EXPECT_NEAR(one[i], running, 1e-5 * running + 1e-3) << i;
    for (size_t k = i; k < std::min(in.size(), i + 997); ++k) running += in[k];
  }
}

TEST(ParallelReduce, SumAndMaxMatchBruteForce) {
  for (size_t n : kSizes) {
    const std::vector<uint32_t> v = random_values(n, 1u << 20, uint32_t(n) + 5);
    const uint64_t sum = parallel_reduce(
        n, uint64_t(0), [&](size_t i) { return uint64_t(v[i]); },
        [](uint64_t a, uint64_t b) { return a + b; });
    const uint32_t largest = parallel_reduce(
        n, uint32_t(0), [&](size_t i) { return v[i]; },
        [](uint32_t a, uint32_t b) { return std::max(a, b); });
    EXPECT_EQ(sum, std::accumulate(v.begin(), v.end(), uint64_t(0))) << n;
    EXPECT_EQ(largest, n == 0 ? 0u : *std::max_element(v.begin(), v.end())) << n;
  }
}

TEST(ParallelReduce, FloatSumIsTheSameWithOneOrTwoThreads) {
  Pcg32 rng(9);
  std::vector<float> v(5 * kScanBlock + 3);
  for (float& x : v) x = rng.next_float() - 0.3f;
  const auto sum = [&] {
    return parallel_reduce(
        v.size(), 0.0f, [&](size_t i) { return v[i]; }, [](float a, float b) { return a + b; });
  };
  float one, two;
  {
    ThreadLimit limit(1);
    one = sum();
  }
  {
    ThreadLimit limit(2);
    two = sum();
  }
  EXPECT_EQ(one, two);
  EXPECT_NEAR(one, std::accumulate(v.begin(), v.end(), 0.0), 0.05);
}

TEST(SortByKey, MatchesAStableSortOfThePairs) {
  for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(999), size_t(70001)}) {
    for (int bits : {32, 12, 1}) {
      const uint32_t bound = bits == 32 ? 0xFFFFFFFFu : (1u << bits);
      std::vector<uint32_t> keys = random_values(n, bound, uint32_t(n) * 31 + bits);
      // Many equal keys when bits is small: the values (input positions) check stability.
      std::vector<uint32_t> values(n);
      std::iota(values.begin(), values.end(), 0u);
      std::vector<std::pair<uint32_t, uint32_t>> expected(n);
      for (size_t i = 0; i < n; ++i) expected[i] = {keys[i], values[i]};
      std::stable_sort(expected.begin(), expected.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      sort_by_key(keys, values, bits);
      for (size_t i = 0; i < n; ++i) {
        ASSERT_EQ(keys[i], expected[i].first) << n << " " << bits << " " << i;
        ASSERT_EQ(values[i], expected[i].second) << n << " " << bits << " " << i;
      }
    }
  }
}

TEST(SortByKey, SameResultWithOneOrTwoThreads) {
  const std::vector<uint32_t> keys = random_values(50000, 300, 4);
  std::vector<uint32_t> k1 = keys, k2 = keys, v1(keys.size()), v2(keys.size());
  std::iota(v1.begin(), v1.end(), 0u);
  std::iota(v2.begin(), v2.end(), 0u);
  {
    ThreadLimit limit(1);
    sort_by_key(k1, v1, 9);
  }
  {
    ThreadLimit limit(2);
    sort_by_key(k2, v2, 9);
  }
  EXPECT_EQ(k1, k2);
  EXPECT_EQ(v1, v2);
  EXPECT_TRUE(std::is_sorted(k1.begin(), k1.end()));
}

TEST(SortByKey, RejectsMismatchedSpans) {
  std::vector<uint32_t> keys(3), values(2);
  EXPECT_THROW(sort_by_key(keys, values), Error);
}

}  // namespace
}  // namespace bounce
