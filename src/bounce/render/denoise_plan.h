// What the CPU denoiser (denoiser.cpp) and the GPU's (gpu/device_denoiser.cu) decide the same
// way each frame: which a-trous passes run over which light, and the settings every pass shares.
// One copy, so the two backends cannot drift apart.
#pragma once

#include <algorithm>
#include <limits>

#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoise_half.h"
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
                                          IndirectHistory indirect, bool resized, bool rest_valid) {
  const bool rest = denoise_at_rest(s, state);
  TemporalSettings ts;
  ts.cap_direct = rest ? std::numeric_limits<float>::infinity() : float(std::max(s.history_max, 1));
  ts.cap_clipped = std::min(ts.cap_direct, float(std::max(s.changing_history_max, 1)));
  // Indirect light a technique accumulates itself already holds its history; the denoiser adds a
  // short one only while the camera moves (the technique then re-gathers kept photons from a new
  // view, at a lower resolution). At rest and after a world change (where the technique
  // restarts) a longer one would only lag behind the technique's own average.
  const float accumulated_cap =
      state == HistoryState::kCameraMoved ? float(std::max(s.accumulated_history, 1)) : 1.0f;
  switch (indirect) {
    case IndirectHistory::kPerFrame:
      ts.cap_indirect = ts.cap_direct;
      break;
    case IndirectHistory::kAccumulated:
      ts.cap_indirect = std::min(ts.cap_direct, accumulated_cap);
      break;
    case IndirectHistory::kRing:  // none while the world changes: the ring carries the change in
      ts.cap_indirect = state == HistoryState::kWorldChanged ? 0.0f : ts.cap_direct;
      break;
  }
  ts.history = s.temporal && state != HistoryState::kReset;
  ts.reproject =
      resized || state == HistoryState::kCameraMoved || state == HistoryState::kWorldChanged;
  ts.clip = state == HistoryState::kWorldChanged;
  // Indirect light's history is clipped everywhere the world changed.
  if (ts.clip) ts.cap_indirect = std::min(ts.cap_indirect, ts.cap_clipped);
  ts.rest_continues = rest && rest_valid && !resized;
  ts.clip_gamma = s.clip_gamma;
  ts.depth_tolerance = s.depth_tolerance;
  ts.normal_tolerance = s.normal_tolerance;
  ts.modulation_alpha = s.modulation_alpha;
  return ts;
}

struct AtrousPlan {
  int direct_iterations = 0;    // passes over direct light, at its resolution
  int indirect_iterations = 0;  // passes over indirect light (0: none)
  bool direct_half = false;     // direct light filtered at half resolution
  bool half = false;            // indirect light filtered at half resolution
  // At full resolution with as many passes, both lights share each pass's geometry.
  bool both = false;
  // Direct light (with indirect light when `both`) filtered at full resolution; indirect light
  // filtered at full resolution on its own, after it.
  bool direct_full = false;
  bool indirect_full = false;
  // Nothing is filtered after the half-resolution filter: its upsample remodulates (with direct
  // light filtered at full resolution before it, where it is not filtered there).
  bool upsample_remodulates = false;
  // The spatial variance estimated at half resolution (denoise_variance.h): every light is
  // filtered there and every pixel's history is short.
  bool half_variance = false;
};

// `rest_frames`: consecutive frames at rest up to this one (0 when not at rest);
// `history_frames`: frames since the last reset before this one (0 at a reset); `clipped`: this
// frame's history was clipped to its neighbourhood (TemporalSettings::clipped: the world changed).
inline AtrousPlan atrous_plan(const DenoiseSettings& s, bool spatial, bool has_indirect, int height,
                              int rest_frames, int history_frames, bool clipped) {
  AtrousPlan p;
  p.direct_iterations =
      direct_iterations_at_rest(s.atrous_iterations, s.rest_atrous_frames, rest_frames);
  // A short history holds noise as wide as the full-resolution passes reach: half resolution
  // reaches twice as far, with one pass fewer (steps 1 and 2 there span what 1, 2 and 4 span at
  // full resolution) at a quarter of the cost per pass. So does a history clipped to this
  // frame's noisy neighbourhood, frame after frame while the world changes (a flashlight carried
  // through a level): there the half-resolution passes measured closer to the reference, not only
  // faster (docs/benchmarks.md, stop 47). There they keep every pass, reaching twice as far: with
  // the clipped history at most two frames long (changing_history_max) the light is about one
  // frame's, and the pass more brought the level's walk closer at a millisecond's cost at
  // 1280x720 (docs/benchmarks.md, stop 52).
  p.direct_half = spatial && p.direct_iterations > 0 && s.half_direct_frames > 0 &&
                  (history_frames < s.half_direct_frames || clipped);
  if (p.direct_half && !clipped) p.direct_iterations = std::max(p.direct_iterations - 1, 1);
  p.indirect_iterations =
      spatial && has_indirect ? indirect_iterations_for(s.indirect_iterations, height) : 0;
  if (p.indirect_iterations > 1 && s.rest_indirect_frames > 0 &&
      rest_frames >= s.rest_indirect_frames)
    --p.indirect_iterations;
  p.half = p.indirect_iterations > 0 && s.indirect_resolution == 2;
  p.both = p.indirect_iterations > 0 && !p.half && !p.direct_half &&
           p.indirect_iterations == p.direct_iterations;
  p.direct_full = spatial && !p.direct_half;
  p.indirect_full = p.indirect_iterations > 0 && !p.both && !p.half;
  p.upsample_remodulates = (p.direct_half || p.half) && (!has_indirect || p.half);
  // A pixel's history is at most history_frames long (it restarted at the reset). (Indirect
  // light that is not filtered needs no variance.)
  p.half_variance = p.direct_half && (p.indirect_iterations == 0 || p.half) &&
                    float(history_frames) + 1.0f < kShortHistory;
  return p;
}

// A frame counter one frame on, saturating far below overflow.
inline int next_count(int frames) {
  return std::min(frames, (1 << 30) - 1) + 1;
}

// Passes first .. first + count - 1 of an a-trous filter (steps 2^k) from `pass`'s inputs: over
// its direct slot alone, or over both slots sharing the geometric weights (`both`).
// outputs(k, pass) points pass k's outputs at their planes; passes.atrous(pass, both, variance)
// runs one pass on the backend. The filter ends after pass `end - 1`, whose variance would guide
// nothing. Returns the pass whose inputs are the results.
template <typename Passes, typename Outputs>
AtrousPass run_atrous(const Passes& passes, AtrousPass pass, bool both, int first, int count,
                      int end, const Outputs& outputs) {
  for (int k = first; k < first + count; ++k) {
    outputs(k, pass);
    pass.step = 1 << k;
    passes.atrous(pass, both, k + 1 < end);
    pass.direct.in = pass.direct.out;
    pass.direct.in_var = pass.direct.out_var;
    pass.indirect.in = pass.indirect.out;
    pass.indirect.in_var = pass.indirect.out_var;
  }
  return pass;
}

// The full-resolution a-trous ping-pong, owned by the backend: per pass parity, each light's
// rgb and variance.
struct FullPlanes {
  RgbPlanes direct[2], indirect[2];
  float* direct_var[2] = {};
  float* indirect_var[2] = {};
};

// Direct light's full-resolution passes (plan.direct_full), with indirect light where the plan
// has both share them. Replaces light_d (and light_i) by the results.
template <typename Backend>
void filter_direct_full(const Backend& backend, const AtrousPass& base, const AtrousPlan& plan,
                        const FullPlanes& planes, ConstRgbPlanes& light_d,
                        ConstRgbPlanes& light_i) {
  auto outputs = [&planes](int k, AtrousPass& pass) {
    pass.direct.out = planes.direct[k & 1];
    pass.direct.out_var = planes.direct_var[k & 1];
    pass.indirect.out = planes.indirect[k & 1];
    pass.indirect.out_var = planes.indirect_var[k & 1];
  };
  const int n = plan.direct_iterations;
  const AtrousPass result = run_atrous(backend, base, plan.both, 0, n, n, outputs);
  light_d = result.direct.in;
  if (plan.both) light_i = result.indirect.in;
}

// Indirect light's full-resolution passes on their own (plan.indirect_full), in the pass's direct
// slot with indirect light's luminance sigma. The direct result sits in the direct planes, so
// these write the indirect ones. Replaces light_i by the result.
template <typename Backend>
void filter_indirect_full(const Backend& backend, const AtrousPass& base, const AtrousPlan& plan,
                          const FullPlanes& planes, ConstRgbPlanes& light_i) {
  AtrousPass alone = base;
  alone.direct = base.indirect;
  alone.sigma_luminance = base.sigma_luminance_indirect;
  auto outputs = [&planes](int k, AtrousPass& pass) {
    pass.direct.out = planes.indirect[k & 1];
    pass.direct.out_var = planes.indirect_var[k & 1];
  };
  const int n = plan.indirect_iterations;
  light_i = run_atrous(backend, alone, false, 0, n, n, outputs).direct.in;
}

// The planes the half-resolution filter works in, owned by the backend. Per light slot (the
// lights filtered here, direct first): the downsampled input (0) and the a-trous ping-pong (1,
// 2), each rgb and variance; then the upsampled result at full resolution.
struct HalfPlanes {
  SurfacePlanes surface;
  float* depth_slope = nullptr;
  RgbPlanes light[3][kHalfMaxLights];
  float* variance[3][kHalfMaxLights] = {};
  RgbPlanes upsampled[kHalfMaxLights];
  float* moments[5] = {};  // the blocks' moment sums, for AtrousPlan::half_variance
  int width = 0;
  int height = 0;
};

// What the spatial variance at half resolution reads at full resolution besides the light.
struct HalfVarianceInputs {
  ConstHistoryPlanes history;     // this frame's accumulation, with its moments
  const float* length = nullptr;  // its history length per pixel
  float cap_indirect = 0.0f;
  bool one_frame = false;  // every pixel holds one frame (a reset): neither is read
};

// The lights the plan filters at half resolution (direct_half, half), from `base`'s inputs at
// full resolution: downsampled together, filtered (sharing the geometric weights for the passes
// both take), upsampled together. Replaces light_d and light_i by the results of those filtered
// here. With plan.half_variance the spatial variance is estimated here from `variance`'s
// inputs, and base's variance planes are not read. With plan.upsample_remodulates the upsample
// remodulates into `remodulate`'s images (kRest: `rest`; direct light from remodulate.direct
// where it is not filtered here), and nothing is left to remodulate.
// The backend runs the passes: downsample(HalfDownsample), half_variance(HalfVariancePass),
// depth_slope(depth, w, h, out), atrous(pass, both, variance), upsample(HalfUpsample).
template <typename Backend>
void filter_half(const Backend& backend, const AtrousPass& base, const AtrousPlan& plan,
                 const HalfPlanes& half, const HalfVarianceInputs& variance,
                 const RemodulatePass& remodulate, bool rest, ConstRgbPlanes& light_d,
                 ConstRgbPlanes& light_i) {
  const int nd = plan.direct_half ? plan.direct_iterations : 0;
  const int ni = plan.half ? plan.indirect_iterations : 0;
  if (nd == 0 && ni == 0) return;
  // Slot of each light filtered here (direct first), and its full-resolution input.
  const AtrousLight* inputs[kHalfMaxLights] = {};
  int lights = 0;
  const int slot_d = nd > 0 ? lights++ : -1;
  const int slot_i = ni > 0 ? lights++ : -1;
  if (slot_d >= 0) inputs[slot_d] = &base.direct;
  if (slot_i >= 0) inputs[slot_i] = &base.indirect;

  HalfDownsample down;
  down.surface = base.surface;
  down.lights = lights;
  down.width = base.width;
  down.height = base.height;
  down.half_surface = half.surface;
  down.half_width = half.width;
  for (int l = 0; l < lights; ++l) {
    down.light[l] = inputs[l]->in;
    down.variance[l] = inputs[l]->in_var;
    down.half_light[l] = half.light[0][l];
    down.half_variance[l] = half.variance[0][l];
  }
  if (plan.half_variance) {
    down.moments = variance.one_frame ? BlockMoments::kOneFrame : BlockMoments::kHistory;
    down.history = variance.history;
    down.length = variance.length;
    down.cap_indirect = variance.cap_indirect;
    for (int k = 0; k < 5; ++k) down.half_moments[k] = half.moments[k];
  }
  backend.downsample(down, half.height);
  if (plan.half_variance) {
    // (Direct light is filtered here, so it is slot 0; indirect light, if any, slot 1.)
    HalfVariancePass v;
    for (int k = 0; k < 5; ++k) v.moments[k] = half.moments[k];
    for (int l = 0; l < lights; ++l) v.var[l] = half.variance[0][l];
    v.width = half.width;
    v.height = half.height;
    backend.half_variance(v);
  }
  backend.depth_slope(half.surface.depth, half.width, half.height, half.depth_slope);

  // Slot 0 rides in the pass's direct light, slot 1 in its indirect light.
  AtrousPass pass = base;
  pass.surface = half.surface;
  pass.depth_slope = half.depth_slope;
  pass.width = half.width;
  pass.height = half.height;
  pass.direct = {half.light[0][0], half.variance[0][0], {}, nullptr};
  pass.indirect = {half.light[0][1], half.variance[0][1], {}, nullptr};
  // A lone indirect light takes the direct slot with its own luminance sigma.
  if (slot_d < 0) pass.sigma_luminance = base.sigma_luminance_indirect;
  auto outputs_of = [&](int slot) {
    return [&half, slot](int k, AtrousPass& p) {
      AtrousLight& out = slot == 0 ? p.direct : p.indirect;
      out.out = half.light[1 + (k & 1)][slot];
      out.out_var = half.variance[1 + (k & 1)][slot];
    };
  };
  auto outputs_both = [&](int k, AtrousPass& p) {
    outputs_of(0)(k, p);
    outputs_of(1)(k, p);
  };
  // Both lights share the passes they both take; the one with more passes goes on alone.
  const int shared = lights == 2 ? std::min(nd, ni) : 0;
  pass = run_atrous(backend, pass, true, 0, shared, std::max(nd, ni), outputs_both);
  ConstRgbPlanes filtered[kHalfMaxLights];
  if (lights == 1) {
    filtered[0] =
        run_atrous(backend, pass, false, 0, std::max(nd, ni), std::max(nd, ni), outputs_of(0))
            .direct.in;
  } else if (nd > shared) {
    filtered[0] =
        run_atrous(backend, pass, false, shared, nd - shared, nd, outputs_of(0)).direct.in;
    filtered[1] = pass.indirect.in;
  } else {
    // Indirect light alone in the direct slot, writing the ping-pong's indirect planes.
    AtrousPass alone = pass;
    alone.direct = pass.indirect;
    alone.sigma_luminance = base.sigma_luminance_indirect;
    auto outputs = [&half](int k, AtrousPass& p) {
      p.direct.out = half.light[1 + (k & 1)][1];
      p.direct.out_var = half.variance[1 + (k & 1)][1];
    };
    filtered[0] = pass.direct.in;
    filtered[1] = run_atrous(backend, alone, false, shared, ni - shared, ni, outputs).direct.in;
  }

  HalfUpsample up;
  up.surface = base.surface;
  up.depth_slope = base.depth_slope;
  up.lights = lights;
  up.half_surface = half.surface;
  up.width = base.width;
  up.height = base.height;
  up.half_width = half.width;
  up.half_height = half.height;
  up.sigma_depth = base.sigma_depth;
  for (int l = 0; l < lights; ++l) {
    up.light[l] = inputs[l]->in;
    up.half_light[l] = filtered[l];
    up.out[l] = half.upsampled[l];
  }
  up.remodulated = plan.upsample_remodulates;
  up.indirect_only = slot_d < 0;
  up.rest = rest;
  up.remodulate = remodulate;
  backend.upsample(up);
  if (slot_d >= 0) light_d = half.upsampled[slot_d];
  if (slot_i >= 0) light_i = half.upsampled[slot_i];
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
