// The path-tracing kernel: radiance along one path, unbiased, with next-event estimation and
// multiple importance sampling. Plain functions over plain data (no allocation, exceptions or
// virtual calls besides the Tracer's ray queries), shared by the `path` technique and the offline
// reference renderer. README.md in this folder explains the estimator and its choices.
#pragma once

#include <cstdint>

#include "bounce/core/math.h"
#include "bounce/core/rng.h"
#include "bounce/render/brdf.h"
#include "bounce/scene/scene.h"
#include "bounce/render/light_picker.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// How light from area and sphere lights is estimated at each vertex. kMis is the estimator; the
// other two exist to check it (each alone is unbiased too, with more variance).
enum class LightStrategy : uint8_t { kMis, kLightOnly, kBsdfOnly };

// Paths never get longer than this many bounces, even with no limit set: only a white furnace
// (albedo 1, where Russian roulette never ends a path) gets there.
inline constexpr int kMaxPathBounces = 1024;

struct PathSettings {
  // Light is counted by its indirect bounces: the surfaces it reflected off between leaving an
  // emitter and reaching the start vertex (which reflects it towards the viewer). Direct light
  // has 0 bounces. Paths count light with min_bounces..max_bounces bounces; max_bounces < 0
  // means no limit. The reference uses min 0; the technique's indirect term uses min 1.
  int min_bounces = 0;
  int max_bounces = -1;
  // Russian roulette decides every continuation from vertex rr_start on (vertex 0 is the start):
  // the path survives with probability min(1, max channel of its throughput).
  int rr_start = 3;
  LightStrategy strategy = LightStrategy::kMis;
};

struct PathScene {
  const Scene& scene;
  const Tracer& tracer;
  const LightPicker& lights;
};

// A surface point a path leaves from.
struct PathVertex {
  vec3 position;
  vec3 geometric_normal;  // on the side the path arrived from
  SurfacePoint surface;   // shading normal (same side) and material
};

struct PathCounters {
  uint64_t rays = 0;       // intersection and shadow rays
  uint64_t nonfinite = 0;  // samples dropped because they were NaN or infinite
};

// The generator of one path: a function of the pixel, the sample index and the seed only, so
// images do not depend on how the work is split over threads.
Pcg32 path_rng(uint32_t pixel, uint32_t sample, uint32_t seed);

// Radiance that `start` reflects towards wo (its own emission excluded), from light with
// settings.min_bounces..max_bounces bounces.
vec3 reflected_radiance(const PathScene& ps, const PathSettings& settings, const PathVertex& start,
                        vec3 wo, Pcg32& rng, PathCounters& counters);

// Radiance arriving at `origin` from unit direction -direction: what a camera ray sees, emitters
// included (their emission at weight one: no light sample is taken at a camera).
vec3 ray_radiance(const PathScene& ps, const PathSettings& settings, vec3 origin, vec3 direction,
                  Pcg32& rng, PathCounters& counters);

}  // namespace bounce
