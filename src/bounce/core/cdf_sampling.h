// Sampling a discrete distribution from its cumulative table: which light to sample, which
// triangle of an area light. A plain function over a pointer and a size, so that kernels can
// call it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct CdfSample {
  uint32_t entry = 0;
  float u = 0.0f;  // the sample stretched back over [0, 1) within the entry's interval
};

// u, which fell in an entry's interval [start, end) (cdf[entry - 1], 0 for entry 0, and
// cdf[entry]), stretched back over [0, 1) within it, so that the caller can reuse the same number
// inside the entry and keep its stratification.
BOUNCE_HD inline float cdf_stretch_within(float start, float end, float u) {
  const float span = end - start;
  // The clamp keeps u below 1 when rounding (or u past the table's end) would reach it.
  const float stretched = glm::clamp((u - start) / span, 0.0f, 0.99999994f);
  return span > 0.0f ? stretched : 0.5f;
}
// The same for `entry` of the table. Written as selects over loads that are always valid (entry 0
// reads its own entry as the one before, then takes 0), so a row of pixels' stretches vectorise
// (render/direct.cpp).
// (Index: uint32_t, or int where a CPU row loop gathers: src/CMakeLists.txt.)
template <typename Index>
BOUNCE_HD inline float cdf_stretch(const float* cdf, Index entry, float u) {
  const float before = cdf[entry - Index(entry != 0)];
  const float start = entry == 0 ? 0.0f : before;
  return cdf_stretch_within(start, cdf[entry], u);
}

// Entry k owns [cdf[k - 1], cdf[k]) (cdf[-1] = 0), so u on a boundary goes to the entry above it
// and an entry of zero probability is never chosen; u at or above cdf[count - 1] gives the last
// entry. count must be at least 1; cdf must not decrease.
//
// The search is branch-free and takes the same number of steps for every u (cdf_halve), so a row
// of pixels can run their searches in lockstep (render/direct.cpp): no mispredicted branch, and
// one pixel's loads overlap the others'.
// One step over the `len` entries from `base` that may hold u's (half = len / 2, then len shrinks
// by half): the first half are passed over if entry base + half ends at or below u. cdf_entry
// finishes once len is 1.
template <typename Index>
BOUNCE_HD inline Index cdf_halve(const float* cdf, Index base, Index half, float u) {
  return cdf[base + half] <= u ? base + half : base;
}
template <typename Index>
BOUNCE_HD inline Index cdf_entry(const float* cdf, Index base, Index count, float u) {
  const Index entry = base + Index(cdf[base] <= u);
  return entry < count ? entry : count - 1;
}
// Calls step(half) for each of the search's steps over a table of `count` entries.
template <typename Step>
BOUNCE_HD inline void for_cdf_halves(uint32_t count, Step&& step) {
  for (uint32_t len = count; len > 1;) {
    const uint32_t half = len / 2;
    step(half);
    len -= half;
  }
}
BOUNCE_HD inline CdfSample sample_cdf(const float* cdf, size_t count, float u) {
  uint32_t base = 0;
  for_cdf_halves(uint32_t(count), [&](uint32_t half) { base = cdf_halve(cdf, base, half, u); });
  const uint32_t entry = cdf_entry(cdf, base, uint32_t(count), u);
  return {entry, cdf_stretch(cdf, entry, u)};
}

}  // namespace bounce
