// The offline reference: a full image path-traced from the camera, converged by samples per pixel
// or a time limit. Every technique is measured against its output.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene.h"
#include "bounce/techniques/path/path_tracer.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// Sample indices per pixel stay below this (2^30), so first sample + count fits an int.
inline constexpr int kMaxReferenceSample = 1 << 30;

struct ReferenceSettings {
  int width = 256;
  int height = 256;
  int spp = 256;  // samples per pixel to take
  // The index of the first of them in each pixel's sample sequence: a run with first_sample K
  // takes samples K .. K + spp - 1 of the sequence a run from 0 would take, so runs over
  // disjoint slices (on different machines) merge into the image of one long run.
  int first_sample = 0;
  double time_limit_s = 0.0;  // stop earlier once this much time has passed (0: no limit)
  uint32_t seed = 0;
  PathSettings path;  // min_bounces is ignored: a reference counts all light from 0 bounces
};

struct ReferenceProgress {
  int spp_done = 0;
  int spp_target = 0;
  double elapsed_s = 0.0;
  double fraction = 0.0;  // of the work, by samples or by the time limit, whichever is further
  double eta_s = 0.0;     // estimated seconds left
};

struct ReferenceResult {
  Image image;  // linear radiance: each pixel the mean over its square (a box filter)
  int spp = 0;  // samples per pixel taken (fewer than asked when the time limit ended the run)
  double seconds = 0.0;
  uint64_t rays = 0;
  uint64_t nonfinite = 0;  // samples dropped as NaN or infinite (0 unless something is wrong)
};

using ReferenceProgressFn = std::function<void(const ReferenceProgress&)>;

// Where a progressive reference stands: per-pixel sums of the samples taken so far, in sample
// order. Samples are numbered per pixel, so a run that starts from a state continues exactly
// where the interrupted one stopped: the resumed image equals an uninterrupted one.
struct ReferenceState {
  int width = 0, height = 0;
  int spp = 0;               // samples per pixel in the sums
  std::vector<double> sums;  // 3 per pixel, row-major
};

// What a checkpoint file must match to be resumed: the image and the light transport settings.
// `scene` names the scene (its source, and the animation time).
struct ReferenceCheckpointKey {
  std::string scene;
  int width = 0, height = 0;
  uint32_t seed = 0;
  int max_bounces = -1, rr_start = 3;
  int first_sample = 0;  // the slice's first sample (ReferenceSettings::first_sample)
  int light_candidates = PathSettings().light_candidates;  // PathSettings::light_candidates
  bool operator==(const ReferenceCheckpointKey&) const = default;
};

// The key as NAME=VALUE text fields (scene, width, height, seed, max_bounces, rr_start,
// sample_offset, light_candidates, and the version of the next-event estimate's scheme): what a
// checkpoint file and a reference image's EXR header record.
std::map<std::string, std::string> reference_key_fields(const ReferenceCheckpointKey& key);

// Saves the state atomically (a temporary file renamed over `path`), in a binary file that
// starts with the key; loads it back, failing with a message naming the file when it is not a
// checkpoint, is damaged, or was made with another key.
void save_reference_checkpoint(const std::string& path, const ReferenceCheckpointKey& key,
                               const ReferenceState& state);
ReferenceState load_reference_checkpoint(const std::string& path,
                                         const ReferenceCheckpointKey& key);

// Renders the scene through `camera` on all cores, in passes of whole samples per pixel (a pass
// lasts about half a second); `progress` is called after each pass. The image for a given spp
// and seed is the same whatever the thread count and the pass sizes.
// With `state`, the run starts from its samples (it must be of the settings' size, with fewer
// samples than settings.spp) and leaves the sums there after every pass, so a progress callback
// can checkpoint them.
ReferenceResult render_reference(const Scene& scene, const Tracer& tracer, const Camera& camera,
                                 const ReferenceSettings& settings,
                                 const ReferenceProgressFn& progress = {},
                                 ReferenceState* state = nullptr);

}  // namespace bounce
