#include "bounce/core/resident_memory.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

namespace bounce {
namespace {

TEST(ResidentMemory, GrowsByWhatIsTouched) {
  const uint64_t before = resident_memory_bytes();
  ASSERT_GT(before, 0u) << "/proc/self/statm should be readable on Linux";
  constexpr size_t kSize = size_t(64) << 20;
  auto block = std::make_unique<unsigned char[]>(kSize);
  std::memset(block.get(), 1, kSize);  // touched pages become resident
  const uint64_t after = resident_memory_bytes();
  EXPECT_GE(after, before + kSize * 9 / 10);
  EXPECT_EQ(block[kSize - 1], 1);
}

TEST(ResidentMemory, GrowthIsThePeakAfterWarmupOverTheFirstSampleAfterIt) {
  MemorySamples s;
  s.add(10, 500);  // warm-up: ignored
  s.add(20, 900);
  s.add(30, 1000);
  s.add(40, 1010);
  s.add(50, 1005);
  EXPECT_NEAR(s.growth_after(30), 0.01, 1e-12);
  EXPECT_NEAR(s.growth_after(25), 0.01, 1e-12);  // from the first sample at or after frame 25
  EXPECT_NEAR(s.growth_after(0), 1.02, 1e-12);   // 1010 / 500 - 1
  EXPECT_DOUBLE_EQ(s.growth_after(50), 0.0);     // one sample: no growth to measure
  EXPECT_DOUBLE_EQ(s.growth_after(60), 0.0);     // none
  MemorySamples falling;
  falling.add(0, 1000);
  falling.add(1, 900);
  EXPECT_DOUBLE_EQ(falling.growth_after(0), 0.0);  // shrinking is not growth
}

}  // namespace
}  // namespace bounce
