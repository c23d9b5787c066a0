#include "bounce/techniques/path/path_technique.h"

#include <algorithm>
#include <atomic>

#include "bounce/core/parallel.h"

namespace bounce {

PathTracing::PathTracing() {
  params_.add_int("max_bounces", &max_bounces_, -1, kMaxPathBounces,
                  "indirect bounces counted (0: none; -1: no limit, Russian roulette ends paths)");
  params_.add_int("rr_start", &rr_start_, 0, kMaxPathBounces,
                  "path vertex from which Russian roulette may end a path");
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

  const PathScene ps{context.scene, context.tracer, lights_};
  PathSettings settings;
  settings.min_bounces = 1;
  settings.max_bounces = max_bounces_;
  settings.rr_start = rr_start_;
  // Without accumulation every frame still draws new paths.
  const uint32_t first =
      uint32_t(accumulate ? frames_ : int(context.frame_index)) * uint32_t(samples_);
  const vec3 eye = context.camera.origin;
  const float inv = 1.0f / float((frames_ + 1) * samples_);
  std::atomic<uint64_t> rays{0};
  parallel_for_tiles(g.width, g.height, 8, [&](int x0, int y0, int x1, int y1) {
    PathCounters counters;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t i = size_t(y) * g.width + x;
        if (g.hit(i)) {
          const PathVertex v{g.position[i],
                             g.geometric_normal[i],
                             {g.normal[i], g.albedo[i], g.roughness[i], g.f0[i]}};
          const vec3 wo = glm::normalize(eye - g.position[i]);
          vec3 sum(0.0f);
          for (int k = 0; k < samples_; ++k) {
            Pcg32 rng = path_rng(uint32_t(i), first + uint32_t(k), uint32_t(seed_));
            sum += reflected_radiance(ps, settings, v, wo, rng, counters);
          }
          sums_[i] += sum;
        }
        out.pixels()[i] = sums_[i] * inv;
      }
    rays += counters.rays;
  });
  ++frames_;
  context.counters.rays += rays;
}

}  // namespace bounce
