// The interface a global-illumination technique implements to plug into the frame pipeline.
// A technique sees the scene, the tracer and the G-buffer, and writes indirect radiance; it owns
// its data (photon maps, hit buffers) and times its own sub-stages.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/timer.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/params.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// What a technique did in one frame, for benchmarks (photons per second, rays per second).
struct TechniqueCounters {
  uint64_t photon_paths = 0;
  uint64_t photons_stored = 0;
  uint64_t rays = 0;
};

struct FrameContext {
  const Scene& scene;
  const Tracer& tracer;
  const GBuffer& gbuffer;
  const CameraRays& camera;
  uint32_t frame_index;  // counts frames since the pipeline started
  StageTimes& times;     // a technique adds its sub-stages here, named "indirect/..."
  TechniqueCounters& counters;
};

class Technique {
 public:
  virtual ~Technique() = default;
  virtual std::string name() const = 0;
  // Whether this technique computes indirect light at all (the "direct" technique does not).
  virtual bool has_indirect() const { return true; }
  ParamSet& params() { return params_; }
  // Called when the scene or its lights changed: accumulated state must restart.
  virtual void scene_changed(const Scene& scene, const Tracer& tracer) {}
  // Writes indirect radiance for every G-buffer pixel into `out` (already sized and zeroed).
  virtual void indirect(const FrameContext& context, Image& out) = 0;

 protected:
  ParamSet params_;
};

}  // namespace bounce
