// The contract between the frame pipeline and a global-illumination technique.
//
// Each frame the Renderer works out what changed since the last one (a SceneChange) and calls
//   prepare(PrepareContext)  - work that depends on the scene, not the pixels (photon maps,
//                              refined meshes, hit buffers, refits), timed as "prepare";
//   indirect(FrameContext)   - indirect radiance for every G-buffer pixel, timed as "indirect".
// A technique owns its data, names its sub-stages ("prepare/...", "indirect/..."), declares its
// parameters (ParamSet, shown by the CLI's --help and the viewer's panel) and its command-line
// options. Accumulation over frames is the pipeline's setting (FrameSettings::accumulate): a
// technique continues its running average only when the context says it may.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/timer.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/indirect_history.h"
#include "bounce/render/params.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// What a technique did in one frame, for benchmarks (photons per second, rays per second).
struct TechniqueCounters {
  uint64_t photon_paths = 0;    // traced
  uint64_t photons_stored = 0;  // the frame's photons, those reused included
  uint64_t photons_reused = 0;  // kept from an identical earlier trace instead of retraced
  uint64_t rays = 0;
};

struct PrepareContext {
  const Scene& scene;
  SceneView scene_view;  // the scene as kernels read it (kept current by the Renderer)
  const Tracer& tracer;
  const SceneChange& change;  // since the last frame (SceneChange::all() on the first)
  bool accumulate;            // FrameSettings::accumulate
  uint32_t frame_index;       // counts frames since the pipeline started
  StageTimes& times;          // sub-stages go here, named "prepare/..."
  TechniqueCounters& counters;

  // Whether state accumulated over earlier frames may go on: accumulation is on and nothing
  // that the technique's estimate depends on changed.
  bool continue_accumulation() const { return accumulate && !change.any(); }
};

struct FrameContext {
  const Scene& scene;
  SceneView scene_view;
  const Tracer& tracer;
  const GBuffer& gbuffer;
  const CameraRays& camera;
  const SceneChange& change;
  bool accumulate;
  uint32_t frame_index;
  StageTimes& times;  // sub-stages go here, named "indirect/..."
  TechniqueCounters& counters;

  bool continue_accumulation() const { return accumulate && !change.any(); }
};

// A command-line option a technique declares (e.g. tiled's --photons): `flag` without dashes;
// `apply` sets the technique's parameters from the option's text (throws Error when bad).
struct TechniqueOption {
  std::string flag;
  std::string help;
  std::function<void(ParamSet&, const std::string&)> apply;
};
// An option whose value goes straight to parameter `param`.
TechniqueOption param_option(const std::string& flag, const std::string& param,
                             const std::string& help);

class Technique {
 public:
  virtual ~Technique() = default;
  virtual std::string name() const = 0;
  // Whether this technique computes indirect light at all (the "direct" technique does not).
  virtual bool has_indirect() const { return true; }
  virtual IndirectHistory indirect_history() const { return IndirectHistory::kPerFrame; }
  ParamSet& params() { return params_; }
  const ParamSet& params() const { return params_; }
  // Command-line options beyond --param NAME=VALUE.
  virtual std::vector<TechniqueOption> options() const { return {}; }
  // Parameter assignments ("name=value") a still image affords over a real-time frame (render
  // applies them unless the user sets the parameter).
  virtual std::vector<std::string> still_defaults() const { return {}; }

  // Bytes the technique will keep beyond the per-pixel buffers (photons held across frames,
  // refined meshes) for `scene` with its current parameters, estimated before any frame so that a
  // setting that cannot fit is refused at once (render/memory_estimate.h).
  virtual uint64_t memory_estimate(const Scene& scene) const { return 0; }

  virtual void prepare(const PrepareContext& context) {}
  // Per-pixel work of indirect() that reads only the G-buffer, which the Renderer may run band
  // by band inside its G-buffer pass, while each band's G-buffer is still in the core's cache
  // (at 1280 x 720 the G-buffer is three times the last-level cache). The Renderer calls
  // begin_gbuffer_bands(context) before that pass (context.gbuffer sized, not yet written); when
  // it returns a sub-stage name (the band work is timed as it), gbuffer_band(x0, y0, x1, y1) for
  // every band of whole rows right after the band's G-buffer (from several threads at once,
  // bands disjoint), and the next indirect() finds that work done. The default (an empty name):
  // indirect() does it all.
  virtual std::string begin_gbuffer_bands(const FrameContext& context) { return {}; }
  virtual void gbuffer_band(int x0, int y0, int x1, int y1) {}
  // Writes indirect radiance for every G-buffer pixel into `out` (already sized, and zeroed
  // unless indirect_overwrites()).
  virtual void indirect(const FrameContext& context, Image& out) = 0;
  // Whether indirect() assigns every pixel of `out`, so that the Renderer need not zero it first
  // (11 MB at 1280 x 720).
  virtual bool indirect_overwrites() const { return false; }

 protected:
  ParamSet params_;
};

}  // namespace bounce
