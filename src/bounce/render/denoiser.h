// Temporal reuse and spatial denoising of a frame's light, after Schied et al. 2017,
// "Spatiotemporal Variance-Guided Filtering" (SVGF). A pipeline stage of the Renderer, run after
// direct and indirect light, before composite, for every technique.
//
// Per frame, on direct light (emission seen directly set apart) and indirect light separately:
//  1. demodulate by the G-buffer's albedo, so texture detail is not blurred;
//  2. reproject last frame's history through the G-buffer's motion vectors; a history sample is
//     kept only where depth, normal and object id agree (disocclusion test), else the pixel's
//     history length restarts at zero;
//  3. blend: alpha = max(1 / history_length, 1 / cap), with luminance moments alongside, after
//     clipping the history to the current frame's neighbourhood (mean +- gamma sigma) when the
//     world changed, so moved lights and objects leave no ghosts;
//  4. an edge-avoiding a-trous wavelet filter guided by depth, normals and the luminance variance
//     of the accumulated estimate (it fades as history grows, so frames at rest converge to the
//     unbiased average); indirect light at half resolution, where the same passes reach twice as
//     far for a quarter of the cost, then a joint-bilateral upsample;
//  5. remodulate, add the emission back.
// The unfiltered accumulation is the next frame's history.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/timer.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/indirect_history.h"
#include "bounce/render/light_change_region.h"
#include "bounce/render/params.h"

namespace bounce {

struct DenoiseSettings {
  bool temporal = true;       // temporal accumulation through reprojection
  bool spatial = true;        // the a-trous filter
  int atrous_iterations = 3;  // a-trous passes over direct light (step 1, 2, 4, ...)
  // After this many frames at rest, direct light gets one a-trous pass fewer, and one fewer per
  // doubling after that, down to one (0: never). The mean of a long history needs less
  // filtering (direct_iterations_at_rest).
  int rest_atrous_frames = 32;
  // For this many frames after a reset (the first frame of a still or of a new view, when no
  // pixel has history), and while the world changes (the history clipped every frame), direct
  // light is filtered at half resolution, as indirect light is, with one a-trous pass fewer (0:
  // never). One frame's light samples leave noise wider than the full-resolution passes reach.
  int half_direct_frames = 4;
  // a-trous passes over indirect light at its resolution, for an image 512 pixels high; one
  // more per doubling of the height, one fewer per halving (indirect_iterations_for)
  int indirect_iterations = 5;
  // After this many frames at rest, indirect light gets one a-trous pass fewer (0: never). A long
  // average's blotches are small, and the full filter then blurs real detail: on the Cornell box
  // one pass fewer lowers MSE8 by a quarter to a half from frame 64 on, two fewer raise it.
  int rest_indirect_frames = 64;
  // Indirect light is filtered at 1/indirect_resolution of the width and height (1 or 2), then
  // upsampled guided by depth and normals (render/denoise_half.h).
  int indirect_resolution = 2;
  float sigma_luminance = 4.0f;  // luminance edge-stopping, in standard deviations
  // The same for indirect light; 0: none. Photon gathers leave blotches as wide as the gather
  // radius, which a neighbourhood's variance cannot tell from signal: indirect light is filtered
  // by geometry alone, which also spares its variance (measured on the Cornell box's first
  // frame: MSE8 34.55 at 1e3, 33.18 at 1e5, 33.17 at 1e6 and without).
  float sigma_luminance_indirect = 0.0f;
  float sigma_normal = 128.0f;  // normal edge-stopping exponent
  float sigma_depth = 1.0f;     // depth edge-stopping, relative to the local depth gradient
  int history_max = 32;         // frames of history a pixel keeps while anything moves
  // The same where the world changed (kWorldChanged) and the history is clipped to this frame's
  // neighbourhood: direct light where the change of lights reached (everywhere unless only spot
  // lights changed), indirect light everywhere; at most history_max. A long average of history
  // clipped to one noisy frame's box lags the moving light and blurs what it reprojects: against
  // path-traced references of the level's flashlight walk at 30 fps, 2 frames scored MSE8
  // 31.3 / 7.6 / 58.7 at 1, 2 and 3 s where 32 scored 54.3 / 18.7 / 67.5, and the dynamic
  // Cornell box and ball came a little closer too (docs/benchmarks.md, stop 52).
  int changing_history_max = 2;
  int accumulated_history = 4;  // the same, while the camera moves, for indirect light a
                                // technique accumulates itself (else 1)
  // Variance clipping box half-width in sigmas (world changes). Against path-traced references of
  // scenes where a light or an object moves (the level's flashlight walk, the dynamic Cornell box
  // and ball), 0.5 came closer than the 1.25 of earlier stops in every frame measured: a
  // neighbourhood of one noisy frame has a wide sigma, and a wider box kept stale light
  // (docs/benchmarks.md, stop 48).
  float clip_gamma = 0.5f;
  // In motion, this frame's weight in the albedo and emission that light is remodulated with,
  // blended with last frame's where the pixel sees the same surface (temporal_blend); 1:
  // this frame's alone. Measured on the level's walk: 0.5 came closest to the references, 0.25
  // and 0.8 less close (docs/benchmarks.md, stop 51).
  float modulation_alpha = 0.5f;
  float depth_tolerance = 0.05f;  // disocclusion: relative depth difference
  float normal_tolerance = 0.9f;  // disocclusion: minimum normal agreement (cosine)

  bool operator==(const DenoiseSettings&) const = default;
};

// How this frame's history relates to the last frame's (chosen by the Renderer from the
// SceneChange and FrameSettings).
enum class HistoryState {
  kReset,         // no usable history: first frame, new size, technique or parameters
  kRest,          // nothing changed: running average, no cap on the history length
  kCameraMoved,   // only the camera moved: reproject, history capped at history_max
  kWorldChanged,  // lights, materials or meshes changed: reproject, cap, clip the history
};

// What the viewer shows instead of the denoised image (debug views); not a parameter, so
// switching it keeps the history.
enum class DenoiseView {
  kDenoised,  // the pipeline's image
  kRaw,       // this frame's light as the techniques produced it, before any reuse
  kHistory,   // history length per pixel (black: none, white: history_max or more)
  kMotion,    // screen-space motion (red: x, green: y; 0.5 is still)
  kVariance,  // the luminance variance that guides the filter
};

// The a-trous passes over indirect light for an image `height` pixels high: `iterations` at 512,
// one more per doubling, at least 1 (0 when `iterations` is 0) and at most 8. Photon blotches
// cover a fixed part of the view, so the filter's reach follows the image.
int indirect_iterations_for(int iterations, int height);

// The a-trous passes over direct light after `rest_frames` frames at rest (0 when not at rest):
// `iterations` below `fade_frames`, then one fewer per doubling of the frames, at least 1 (0 when
// `iterations` is 0); all of them when `fade_frames` is 0. History-length-adaptive filtering, as
// SVGF's descendants do: the accumulated mean's noise falls with the frames it averages.
int direct_iterations_at_rest(int iterations, int fade_frames, int rest_frames);

struct DenoiseFrame {
  const GBuffer& gbuffer;  // this frame's, with motion filled
  HistoryState state;
  IndirectHistory indirect_history;  // the technique's: how long a history its light keeps
  StageTimes& times;                 // sub-stages "denoise/..."
  // Whether a later frame may continue this one's history. Without (every frame a reset:
  // FrameSettings::accumulate off) a reset does not start the rest averages no frame will read.
  bool history_continues = true;
  // Where direct light's history is clipped when the world changed (LightChangeRegion): the
  // Renderer narrows it to the cones of the spot lights that moved when nothing else changed.
  LightChangeRegion direct_region = LightChangeRegion::all();
  // Light added to the emission (null: none; the G-buffer's size): the light of the lights the
  // Renderer shades apart, exact in each frame; in motion averaged with the emission, its history
  // clamped to this frame's neighbourhood (denoise::TemporalPass::exact).
  const Image* exact = nullptr;
};

class Denoiser {
 public:
  Denoiser();
  ~Denoiser();
  // params() points into settings(): neither copied nor moved.
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;
  ParamSet& params() { return params_; }
  const ParamSet& params() const { return params_; }
  DenoiseSettings& settings() { return settings_; }
  const DenoiseSettings& settings() const { return settings_; }

  // Replaces `direct` (direct light plus the emission the G-buffer saw) and, when not null,
  // `indirect` by their accumulated and filtered versions, in place. Images are the G-buffer's
  // size. Keeps what the next frame reprojects.
  void run(const DenoiseFrame& frame, Image& direct, Image* indirect);

  // Writes a debug view of the last run into `out` (sized to match). kRaw and kDenoised need
  // keep_raw(true) before the run (it keeps copies of the run's input and output), kMotion
  // keep_motion(true) (a copy of the G-buffer's motion).
  void debug_view(DenoiseView view, Image& out) const;
  void keep_raw(bool keep) { keep_raw_ = keep; }
  void keep_motion(bool keep) { keep_motion_ = keep; }
  // Per pixel history length of the last run (frames), for tests and the debug view.
  const std::vector<float>& history_length() const { return history_length_; }

 private:
  DenoiseSettings settings_;
  ParamSet params_;
  bool keep_raw_ = false;
  bool keep_motion_ = false;
  std::vector<float> history_length_;
  // History colour and moments per channel, previous depth, normal and object id, ping-pong
  // filter planes, raw copies (denoiser.cpp).
  struct Buffers;
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace bounce
