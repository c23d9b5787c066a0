#include "bounce/techniques/path/path_technique.h"

#include <tbb/enumerable_thread_specific.h>

#include "bounce/core/parallel.h"

namespace bounce {

PathTracing::PathTracing() {
  params_.add_int("max_bounces", &max_bounces_, -1, kMaxPathBounces,
                  "indirect bounces counted (0: none; -1: no limit, Russian roulette ends paths)");
  params_.add_int("rr_start", &rr_start_, 0, kMaxPathBounces,
                  "path vertex from which Russian roulette may end a path");
  params_.add_int("light_candidates", &light_candidates_, 1, 64,
                  "scenes with many lights: light samples drawn by power per next-event "
                  "estimate, one kept by its unshadowed contribution (with 2-8 lights a sample "
                  "of each; 1: one light drawn by power)");
  params_.add_int("samples", &samples_, 1, 4096, "paths per pixel per frame");
  params_.add_int("seed", &seed_, 0, 1 << 30, "seed of the paths' random numbers");
}

void PathTracing::prepare(const PrepareContext& context) {
  const SceneChange& c = context.change;
  if (c.geometry() || c.lights || c.materials) lights_ = LightPicker::build(context.scene);
}

void PathTracing::indirect(const FrameContext& context, Image& out) {
  const GBuffer& g = context.gbuffer;
  if (!context.continue_accumulation() || sums_.size() != g.size()) {
    sums_.assign(g.size(), vec3(0.0f));
    frames_ = 0;
  }
  const bool accumulate = context.accumulate;

  const PathScene ps = path_scene(context.scene_view, context.tracer, lights_);
  PathSettings settings;
  settings.min_bounces = 1;
  settings.max_bounces = max_bounces_;
  settings.rr_start = rr_start_;
  settings.light_candidates = light_candidates_;
  // Without accumulation every frame still draws new paths.
  const uint32_t first =
      uint32_t(accumulate ? frames_ : int(context.frame_index)) * uint32_t(samples_);
  const vec3 eye = context.camera.origin;
  const float inv = 1.0f / float((frames_ + 1) * samples_);
  const ConstGBufferView view = g.view();
  const int samples = samples_;
  const uint32_t seed = uint32_t(seed_);
  vec3* sums = sums_.data();
  vec3* pixels = out.pixels().data();
  tbb::enumerable_thread_specific<PathCounters> counters;
  parallel_for_2d(g.width, g.height, [&](int x, int y) {
    const uint32_t i = uint32_t(view.index(x, y));
    sums[i] += path_pixel(ps, settings, view, i, eye, first, samples, seed, counters.local());
    pixels[i] = sums[i] * inv;
  });
  for (const PathCounters& c : counters) context.counters.rays += c.rays;
  ++frames_;
}

}  // namespace bounce
