#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bounce/core/timer.h"

namespace bounce {
namespace {

// Two-pass mean and sample standard deviation, the definition the running moments must match.
void two_pass(const std::vector<double>& v, double& mean, double& stddev) {
  mean = 0.0;
  for (double x : v) mean += x;
  mean /= double(v.size());
  double sq = 0.0;
  for (double x : v) sq += (x - mean) * (x - mean);
  stddev = std::sqrt(sq / double(v.size() - 1));
}

TEST(StageStatistics, MatchesTwoPassMeanAndDeviationWithMissingStagesAsZero) {
  StageStatistics stats;
  std::vector<double> a, b, total;
  for (int k = 0; k < 1000; ++k) {
    StageTimes t;
    const double va = 100.0 + std::sin(0.37 * k) * 3.0;  // a large mean with a small spread
    t.add("a", va);
    a.push_back(va);
    const double vb = (k % 3 == 0) ? 2.0 + 0.01 * k : 0.0;  // "b" only every third frame
    if (k % 3 == 0) t.add("b", vb);
    b.push_back(vb);
    total.push_back(va + vb);
    stats.add(t);
  }
  const auto rows = stats.rows();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(stats.frames(), 1000u);
  const std::vector<double>* series[] = {&a, &b, &total};
  const char* names[] = {"a", "b", "total"};
  for (int i = 0; i < 3; ++i) {
    double mean = 0.0, stddev = 0.0;
    two_pass(*series[i], mean, stddev);
    EXPECT_EQ(rows[size_t(i)].name, names[i]);
    EXPECT_NEAR(rows[size_t(i)].mean_ms, mean, 1e-9 * mean) << names[i];
    EXPECT_NEAR(rows[size_t(i)].stddev_ms, stddev, 1e-9 * stddev) << names[i];
  }
}

TEST(StageStatistics, OneFrameHasNoDeviation) {
  StageStatistics stats;
  StageTimes t;
  t.add("a", 5.0);
  stats.add(t);
  EXPECT_DOUBLE_EQ(stats.rows()[0].mean_ms, 5.0);
  EXPECT_DOUBLE_EQ(stats.rows()[0].stddev_ms, 0.0);
}

}  // namespace
}  // namespace bounce
