// The offline reference: a full image path-traced from the camera, converged by samples per pixel
// or a time limit. Every technique is measured against its output.
#pragma once

#include <cstdint>
#include <functional>

#include "bounce/core/image.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene.h"
#include "bounce/techniques/path/path_tracer.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct ReferenceSettings {
  int width = 256;
  int height = 256;
  int spp = 256;              // samples per pixel to take
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

// Renders the scene through `camera` on all cores, in passes of whole samples per pixel (a pass
// lasts about half a second); `progress` is called after each pass. The image for a given spp
// and seed is the same whatever the thread count and the pass sizes.
ReferenceResult render_reference(const Scene& scene, const Tracer& tracer, const Camera& camera,
                                 const ReferenceSettings& settings,
                                 const ReferenceProgressFn& progress = {});

}  // namespace bounce
