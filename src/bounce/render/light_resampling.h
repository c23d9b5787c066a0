// Resampled importance sampling of light samples (Talbot et al. 2005, "Importance Resampling for
// Global Illumination"; the candidate step of Bitterli et al. 2020, ReSTIR). Of M candidates
// whose one-sample estimates are known before any shadow ray is traced, one is kept with
// probability proportional to its weight and its estimate scaled by (sum of the weights) / (M
// times its own). The expectation over the choice is the mean of the M estimates, so the result
// is unbiased for any positive weights; with the estimates' luminance as weights, the lights that
// are far, behind the surface or facing away are rarely the one traced. A streaming reservoir of
// one: the candidates arrive one at a time.
#pragma once

#include <cstdint>

#include "bounce/core/device.h"

namespace bounce {

// Scenes with more lights than this (LightPicker entries) resample their light samples, direct
// light's (DirectSettings) and the path tracer's next-event estimates (PathSettings), each from
// this many candidates drawn by power.
inline constexpr uint32_t kResampleAboveLights = 8;
inline constexpr int kLightCandidates = 8;

// Whether an offer of weight w, the running sum now `new_total`, replaces the kept one: the first
// is always kept (also where u * total rounds up to w), each later one with probability
// w / total.
BOUNCE_HD inline bool reservoir_takes(float u, float new_total, float w, float kept_so_far) {
  return (u * new_total < w) | (kept_so_far == 0.0f);
}

struct LightReservoir {
  float total = 0.0f;  // the sum of the weights offered
  float kept = 0.0f;   // the kept candidate's weight (0: none yet)

  // Offers a candidate of weight w > 0, decided by the uniform number u; returns whether it is
  // the kept one now.
  BOUNCE_HD bool offer(float w, float u) {
    total += w;
    const bool take = reservoir_takes(u, total, w, kept);
    if (take) kept = w;
    return take;
  }
  BOUNCE_HD bool empty() const { return !(kept > 0.0f); }
};

}  // namespace bounce
