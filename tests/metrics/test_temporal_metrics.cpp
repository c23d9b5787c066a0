// Temporal metrics: flicker and settle time, on synthetic sequences (tests/eval runs them
// through the renderer).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/eval/temporal_runs.h"
#include "bounce/metrics/temporal_metrics.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

namespace bounce {
namespace {

TEST(Flicker, IdenticalFramesDoNotFlicker) {
  Image frame(7, 5, vec3(0.2f, 0.5f, 0.9f));
  frame.at(3, 2) = vec3(4.0f);
  FlickerAccumulator acc;
  for (int k = 0; k < 6; ++k) acc.add(frame);
  EXPECT_EQ(acc.frames(), 6);
  EXPECT_EQ(acc.mean_deviation(), 0.0);
  EXPECT_EQ(acc.flicker(), 0.0);
}

TEST(Flicker, AlternatingFramesGiveHalfTheirDifferenceOverTheirMean) {
  // Population standard deviation of a, b, a, b, ... (an even count) is |a - b| / 2.
  const float a = 0.3f, b = 1.7f;
  std::vector<Image> frames;
  for (int k = 0; k < 8; ++k) frames.emplace_back(6, 4, vec3(k % 2 ? b : a));
  const double expected = (std::abs(double(a) - double(b)) / 2.0) / ((double(a) + double(b)) / 2.0);
  EXPECT_NEAR(flicker(frames), expected, 1e-7);
  FlickerAccumulator acc;
  for (const Image& f : frames) acc.add(f);
  EXPECT_NEAR(acc.mean_deviation(), 0.7, 1e-7);
  EXPECT_NEAR(acc.mean_value(), 1.0, 1e-7);
}

TEST(Flicker, AveragesPerChannelDeviationsOverChannels) {
  // Only the red channel flickers, between 0 and 2: deviation 1 in one channel of three.
  std::vector<Image> frames = {Image(2, 2, vec3(0, 1, 1)), Image(2, 2, vec3(2, 1, 1))};
  FlickerAccumulator acc;
  for (const Image& f : frames) acc.add(f);
  EXPECT_NEAR(acc.mean_deviation(), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(acc.mean_value(), 1.0, 1e-12);
  EXPECT_NEAR(acc.flicker(), 1.0 / 3.0, 1e-12);
}

TEST(Flicker, EdgeCases) {
  FlickerAccumulator acc;
  EXPECT_TRUE(std::isnan(acc.flicker()));
  acc.add(Image(3, 3));
  acc.add(Image(3, 3));
  EXPECT_EQ(acc.flicker(), 0.0);  // all black
  EXPECT_THROW(acc.add(Image(4, 3)), Error);
}

TEST(Flicker, WelfordStaysAccurateOnALargeOffset) {
  // A large constant plus a tiny alternation: a naive sum of squares loses it in float.
  std::vector<Image> frames;
  for (int k = 0; k < 1000; ++k) frames.emplace_back(2, 2, vec3(k % 2 ? 1000.001f : 999.999f));
  const double a = double(999.999f), b = double(1000.001f);
  EXPECT_NEAR(flicker(frames), ((b - a) / 2.0) / ((a + b) / 2.0), 1e-9);
}

TEST(Settle, BlockErrorIsRelativeL1OfBlockSums) {
  Image target(32, 16, vec3(1.0f));
  Image frame = target;
  // Noise that cancels inside a 16x16 block costs nothing.
  frame.at(0, 0) += vec3(0.5f);
  frame.at(1, 0) -= vec3(0.5f);
  EXPECT_NEAR(block_error(block_sums(frame), block_sums(target)), 0.0, 1e-12);
  // The left block 10% too bright: 0.1 * 256 * 3 over 512 * 3.
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) frame.at(x, y) = vec3(1.1f);
  EXPECT_NEAR(block_error(block_sums(frame), block_sums(target)), 0.05, 1e-6);
  // Partial blocks count with their pixels: 20x20 in 16-pixel blocks is 2x2 blocks.
  const BlockSums partial = block_sums(Image(20, 20, vec3(1.0f)));
  EXPECT_EQ(partial.blocks_x, 2);
  EXPECT_EQ(partial.blocks_y, 2);
  EXPECT_DOUBLE_EQ(partial.sums[0], 256.0);
  EXPECT_DOUBLE_EQ(partial.sums[3 * 3], 16.0);
  EXPECT_THROW(block_error(block_sums(Image(16, 16)), block_sums(target)), Error);
  EXPECT_EQ(block_error(block_sums(Image(16, 16)), block_sums(Image(16, 16))), 0.0);
  EXPECT_TRUE(
      std::isinf(block_error(block_sums(Image(16, 16, vec3(1))), block_sums(Image(16, 16)))));
}

TEST(Settle, ASequenceThatReachesTheTargetAtFrameKSettlesAtK) {
  const Image target(32, 32, vec3(2.0f));
  for (int k : {0, 1, 5, 9}) {
    std::vector<Image> frames;
    for (int j = 0; j < 10; ++j)
      // A shrinking gap that stays above 6% until k, then the target (within 1%).
      frames.emplace_back(32, 32, j < k ? vec3(2.0f * (1.06f + 0.5f / float(j + 1))) : vec3(2.01f));
    EXPECT_EQ(settle_frame(frames, target), k) << k;
  }
  // Within tolerance once but not after: it settles only when it stays.
  const std::vector<double> errors = {0.5, 0.01, 0.2, 0.04, 0.03};
  EXPECT_EQ(settle_frame(errors), 3);
  EXPECT_EQ(settle_frame(errors, 0.3), 1);
  EXPECT_EQ(settle_frame(errors, 0.5), 0);
}

TEST(Settle, ASequenceThatNeverSettlesReportsTheSentinel) {
  const Image target(16, 16, vec3(1.0f));
  std::vector<Image> frames;
  for (int j = 0; j < 6; ++j) frames.emplace_back(16, 16, vec3(j % 2 ? 1.2f : 1.0f));
  EXPECT_EQ(settle_frame(frames, target), kNotSettled);  // the last frame is 20% off
  EXPECT_EQ(settle_frame(std::vector<double>{}), kNotSettled);
  const double nan = std::nan("");
  EXPECT_EQ(settle_frame(std::vector<double>{0.0, nan}), kNotSettled);
}

}  // namespace
}  // namespace bounce
