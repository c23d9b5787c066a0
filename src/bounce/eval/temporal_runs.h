// The temporal experiments behind `bounce bench --flicker/--settle`: render a sequence of frames
// through the Renderer and measure it with temporal_metrics.h. Used by the CLI and by tests.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/metrics/temporal_metrics.h"
#include "bounce/render/renderer.h"
#include "bounce/render/technique.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"

namespace bounce {

// Moves the scene's first movable light by `offset` and re-derives the scene: the first point,
// spot or sphere light in `scene.lights` (directional lights have no position), otherwise the
// first area light, whose triangles' vertices are translated (a vertex its mesh shares with
// non-emissive triangles moves with them). Returns what to pass to Renderer::scene_changed:
// {lights} or {moved_meshes = {the mesh}, lights}; nothing (any() false) when no light can move.
// `moved`, when given, receives the light's name.
SceneChange move_first_light(Scene& scene, vec3 offset, std::string* moved = nullptr);
// Whether move_first_light has a light to move.
bool has_movable_light(const Scene& scene);

using TechniqueFactory = std::function<std::unique_ptr<Technique>()>;

// Flicker (temporal_metrics.h) of the linear colour of `frames` frames of the static scene from
// its own camera, after `warmup` frames that are not measured, with FrameSettings::accumulate as
// given: on, at rest as a user sees it (frames average into a converged image); off, every frame
// as while the camera or the scene moves. `settings.jitter` is used as given.
struct FlickerResult {
  double flicker = 0.0;
  double mean_deviation = 0.0;  // the numerator
  double mean_value = 0.0;      // the denominator
};
// `denoise` configures the denoiser when settings.denoise is on.
FlickerResult measure_flicker(const Scene& scene, const TechniqueFactory& make,
                              FrameSettings settings, int warmup, int frames, bool accumulate,
                              const DenoiseSettings& denoise = {});

// Settle time of indirect light after a light moves (temporal_metrics.h):
//  1. rest_frames frames at rest (the technique's state converges on the old lighting);
//  2. move_first_light() by move_fraction * the scene's bounding-box diagonal along `direction`;
//  3. `frames` frames, the block error of each frame's indirect image against the target;
//  4. target_frames more frames at rest: the target is the mean of their indirect images, the
//     technique's own converged indirect light after the move, so that the error measures lag
//     and not the technique's bias.
// FrameSettings::accumulate is on (at rest); the technique is as `make` gives it.
struct SettleOptions {
  int rest_frames = 64;
  int frames = 64;          // the cap: frames measured after the move
  int target_frames = 256;  // several times `frames`, so the target is converged past them
  float move_fraction = 0.1f;
  vec3 direction{1.0f, 0.0f, 0.0f};
  double tolerance = kSettleTolerance;
  int block = kSettleBlock;
};
struct SettleResult {
  // False when the technique has no indirect light (the "direct" technique) or the scene has no
  // light that can move; then nothing was rendered and `reason` says why.
  bool applicable = false;
  std::string reason;
  int settle_frame = kNotSettled;  // temporal_metrics.h; kNotSettled: not within `frames`
  std::vector<double> errors;      // per frame after the move
  double change = 0.0;  // the error of the last frame before the move: how much the move changed
  std::string light;    // the light that moved
  vec3 offset{0.0f};
};
SettleResult measure_settle(const Scene& scene, const TechniqueFactory& make,
                            FrameSettings settings, const SettleOptions& options = {},
                            const DenoiseSettings& denoise = {});

}  // namespace bounce
