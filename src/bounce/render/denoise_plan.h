// What the CPU denoiser (denoiser.cpp) and the GPU's (gpu/device_denoiser.cu) decide the same
// way each frame: which a-trous passes run over which light, and the settings every pass shares.
// One copy, so the two backends cannot drift apart.
#pragma once

#include <algorithm>
#include <limits>

#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoise_temporal.h"
#include "bounce/render/denoiser.h"

namespace bounce::denoise {

// Whether this frame is at rest for the denoiser: history averages without a cap.
inline bool denoise_at_rest(const DenoiseSettings& s, HistoryState state) {
  return state == HistoryState::kRest && s.temporal;
}

// The temporal pass's settings for a frame: how history is reused after `state`, given whether
// the image size changed and whether the rest averages are still valid.
inline TemporalSettings temporal_settings(const DenoiseSettings& s, HistoryState state,
                                          bool indirect_accumulated, bool resized,
                                          bool rest_valid) {
  const bool rest = denoise_at_rest(s, state);
  TemporalSettings ts;
  ts.cap_direct = rest ? std::numeric_limits<float>::infinity() : float(std::max(s.history_max, 1));
  // Indirect light a technique accumulates itself already holds its history; the denoiser adds a
  // short one only while the camera moves (the technique then re-gathers kept photons from a new
  // view, at a lower resolution). At rest and after a world change (where the technique
  // restarts) a longer one would only lag behind the technique's own average.
  const float accumulated_cap =
      state == HistoryState::kCameraMoved ? float(std::max(s.accumulated_history, 1)) : 1.0f;
  ts.cap_indirect = indirect_accumulated ? std::min(ts.cap_direct, accumulated_cap) : ts.cap_direct;
  ts.history = s.temporal && state != HistoryState::kReset;
  ts.reproject =
      resized || state == HistoryState::kCameraMoved || state == HistoryState::kWorldChanged;
  ts.clip = state == HistoryState::kWorldChanged;
  ts.rest_continues = rest && rest_valid && !resized;
  ts.clip_gamma = s.clip_gamma;
  ts.depth_tolerance = s.depth_tolerance;
  ts.normal_tolerance = s.normal_tolerance;
  return ts;
}

struct AtrousPlan {
  int direct_iterations = 0;    // passes over direct light
  int indirect_iterations = 0;  // passes over indirect light (0: none)
  bool half = false;            // indirect light filtered at half resolution
  // At full resolution with as many passes, both lights share each pass's geometry.
  bool both = false;
};

// `rest_frames`: consecutive frames at rest up to this one (0 when not at rest).
inline AtrousPlan atrous_plan(const DenoiseSettings& s, bool spatial, bool has_indirect, int height,
                              int rest_frames) {
  AtrousPlan p;
  p.direct_iterations =
      direct_iterations_at_rest(s.atrous_iterations, s.rest_atrous_frames, rest_frames);
  p.indirect_iterations =
      spatial && has_indirect ? indirect_iterations_for(s.indirect_iterations, height) : 0;
  p.half = p.indirect_iterations > 0 && s.indirect_resolution == 2;
  p.both = p.indirect_iterations > 0 && !p.half && p.indirect_iterations == p.direct_iterations;
  return p;
}

// The first pass over direct (and indirect) light: inputs, the guide planes and the sigmas;
// the outputs are set per pass.
inline AtrousPass atrous_base(const DenoiseSettings& s, ConstSurfacePlanes surface,
                              const float* depth_slope, ConstRgbPlanes direct,
                              const float* direct_var, ConstRgbPlanes indirect,
                              const float* indirect_var, int width, int height) {
  AtrousPass base;
  base.surface = surface;
  base.depth_slope = depth_slope;
  base.direct = {direct, direct_var, {}, nullptr};
  base.indirect = {indirect, indirect_var, {}, nullptr};
  base.width = width;
  base.height = height;
  base.sigma_luminance = s.sigma_luminance;
  base.sigma_luminance_indirect = s.sigma_luminance_indirect;
  base.sigma_normal = s.sigma_normal;
  base.sigma_depth = s.sigma_depth;
  return base;
}

}  // namespace bounce::denoise
