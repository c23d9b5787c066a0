// sample_cdf against a linear scan of the same table, on boundaries, zero-probability entries
// and past the end; the stretched u against its definition.
#include <gtest/gtest.h>

#include <vector>

#include "bounce/core/cdf_sampling.h"
#include "bounce/core/rng.h"

namespace bounce {
namespace {

// The entry whose half-open interval [cdf[k - 1], cdf[k]) holds u, by walking the table.
uint32_t scan(const std::vector<float>& cdf, float u) {
  for (uint32_t k = 0; k < cdf.size(); ++k)
    if (u < cdf[k]) return k;
  return uint32_t(cdf.size()) - 1;
}

TEST(CdfSampling, PicksTheEntryWhoseIntervalHoldsU) {
  // Entry 2 and entry 5 have no probability; the table ends at exactly 1.
  const std::vector<float> cdf = {0.125f, 0.25f, 0.25f, 0.625f, 1.0f, 1.0f};
  Pcg32 rng(17);
  std::vector<float> us = {0.0f, 0.125f, 0.25f, 0.624f, 0.625f, 0.99999994f};
  for (int i = 0; i < 1000; ++i) us.push_back(rng.next_float());
  for (const float u : us) {
    const CdfSample s = sample_cdf(cdf.data(), cdf.size(), u);
    ASSERT_EQ(s.entry, scan(cdf, u)) << u;
    EXPECT_NE(s.entry, 2u) << u;
    EXPECT_NE(s.entry, 5u) << u;
    const float start = s.entry == 0 ? 0.0f : cdf[s.entry - 1];
    EXPECT_NEAR(s.u, (u - start) / (cdf[s.entry] - start), 1e-6f) << u;
    EXPECT_GE(s.u, 0.0f);
    EXPECT_LT(s.u, 1.0f);
  }
  // A boundary belongs to the entry above it, whose stretched u starts at 0.
  EXPECT_EQ(sample_cdf(cdf.data(), cdf.size(), 0.25f).entry, 3u);
  EXPECT_EQ(sample_cdf(cdf.data(), cdf.size(), 0.25f).u, 0.0f);
  EXPECT_EQ(sample_cdf(cdf.data(), cdf.size(), 0.1875f).u, 0.5f);  // middle of entry 1
}

TEST(CdfSampling, AgreesWithTheScanForEveryTableSize) {
  // The binary search at every table size: sizes that are not powers of two, zero-probability
  // runs and u on every boundary and past the end must all land where the scan lands.
  Pcg32 rng(29);
  for (uint32_t count = 1; count <= 70; ++count) {
    std::vector<float> cdf(count);
    float sum = 0.0f;
    for (uint32_t k = 0; k < count; ++k) {
      sum += rng.next_float() < 0.2f ? 0.0f : rng.next_float();
      cdf[k] = sum;
    }
    for (float& c : cdf) c = sum > 0.0f ? c / sum : 1.0f;
    std::vector<float> us(cdf.begin(), cdf.end());
    us.push_back(0.0f);
    us.push_back(0.99999994f);
    for (int i = 0; i < 200; ++i) us.push_back(rng.next_float());
    for (const float u : us)
      ASSERT_EQ(sample_cdf(cdf.data(), count, u).entry, scan(cdf, u)) << count << " " << u;
  }
}

TEST(CdfSampling, StretchedSamplesStayUniformWithinTheEntry) {
  // Stratified u over [0, 1) lands, within each entry, on stratified points over [0, 1).
  const std::vector<float> cdf = {0.25f, 1.0f};
  const int n = 320;  // 240 samples land in entry 1: 30 per bin
  std::vector<int> histogram(8, 0);
  for (int i = 0; i < n; ++i) {
    const CdfSample s = sample_cdf(cdf.data(), cdf.size(), (i + 0.5f) / n);
    if (s.entry == 1) ++histogram[int(s.u * 8.0f)];
  }
  for (int bin = 0; bin < 8; ++bin) EXPECT_EQ(histogram[bin], 30) << bin;
}

TEST(CdfSampling, SingleEntryAndUPastTheEnd) {
  const float one[] = {1.0f};
  EXPECT_EQ(sample_cdf(one, 1, 0.3f).entry, 0u);
  EXPECT_FLOAT_EQ(sample_cdf(one, 1, 0.3f).u, 0.3f);
  // A table that rounding left short of 1: u beyond it still gives the last entry, u below 1.
  const float short_table[] = {0.5f, 0.9999f};
  const CdfSample past = sample_cdf(short_table, 2, 0.99999994f);
  EXPECT_EQ(past.entry, 1u);
  EXPECT_LT(past.u, 1.0f);
  // An entry of zero span that is chosen anyway (the last one) takes the middle.
  const float flat_end[] = {1.0f, 1.0f};
  EXPECT_EQ(cdf_stretch(flat_end, 1, 0.7f), 0.5f);
}

}  // namespace
}  // namespace bounce
