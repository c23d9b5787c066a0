// Our own BVH (trace/bvh.h) against Embree on the CPU, both through the Tracer's stream calls:
// closest hit on incoherent rays (random origins in the scene's bounds, random directions) and on
// coherent ones (camera rays at 512x512 in 8x8 tiles), occlusion on random rays cut at random
// lengths and on shadow rays from the visible points towards the first light; and the build.
// Run: build/release/bench/bounce_microbench --benchmark_filter='Bvh|Embree'
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/light_sampling.h"
#include "bounce/scene/load.h"
#include "bounce/trace/bvh_tracer.h"
#include "bounce/trace/tracer.h"

namespace {

using namespace bounce;

constexpr int kSize = 512;
constexpr size_t kRandomRays = size_t(kSize) * kSize;

struct Scenes {
  Scene scene;
  std::unique_ptr<Tracer> embree, bvh;
  std::vector<Ray> random, random_cut, camera, shadow;
};

Scenes& fixture(const std::string& spec) {
  static std::map<std::string, std::unique_ptr<Scenes>> cache;
  auto& f = cache[spec];
  if (f) return *f;
  f = std::make_unique<Scenes>();
  f->scene = load_scene(spec);
  f->embree = make_embree_tracer(f->scene);
  f->bvh = make_bvh_tracer(f->scene);
  const vec3 lo = f->scene.bounds.lo, extent = f->scene.bounds.hi - lo;
  Pcg32 rng(17);
  for (size_t i = 0; i < kRandomRays; ++i) {
    Ray r;
    r.origin = lo + extent * vec3(rng.next_float(), rng.next_float(), rng.next_float());
    r.direction = sample_uniform_sphere(rng.next2());
    f->random.push_back(r);
    r.tmax = 0.5f * glm::length(extent) * rng.next_float();
    f->random_cut.push_back(r);
  }
  const CameraRays cam = CameraRays::from(f->scene.camera, kSize, kSize);
  for (int ty = 0; ty < kSize; ty += 8)
    for (int tx = 0; tx < kSize; tx += 8)
      for (int y = ty; y < ty + 8; ++y)
        for (int x = tx; x < tx + 8; ++x)
          f->camera.push_back({cam.origin, 0.0f, cam.direction(x + 0.5f, y + 0.5f)});
  GBuffer gbuffer;
  gbuffer.resize(kSize, kSize);
  build_gbuffer(f->scene, *f->embree, cam, vec2(0.5f), gbuffer);
  for (size_t i = 0; i < gbuffer.size(); ++i) {
    if (!gbuffer.hit(i)) continue;
    const vec3 p = gbuffer.position[i];
    const LightSample ls =
        !f->scene.area_lights.empty()
            ? sample_area_light(f->scene, f->scene.area_lights[0], p, hammersley(i % 64, 64))
            : sample_punctual_light(f->scene.lights[0], p);
    if (!ls.valid()) continue;
    f->shadow.push_back(
        {offset_origin(p, gbuffer.geometric_normal[i]), 0.0f, ls.wi, ls.distance * (1.0f - 1e-4f)});
  }
  f->shadow.resize(f->shadow.size() / 64 * 64);
  return *f;
}

// Both cores, 64 rays per call, as the renderer's launchers hand them out.
void run_chunks(benchmark::State& state, size_t count, auto&& chunk) {
  for (auto _ : state)
    parallel_for(
        count / 64, [&](size_t c) { chunk(c * 64, 64); }, 16);
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(count));
}

const Tracer& pick(const Scenes& f, bool bvh) {
  return bvh ? *f.bvh : *f.embree;
}

void BM_Closest(benchmark::State& state, const std::string& spec, bool bvh, bool coherent) {
  Scenes& f = fixture(spec);
  const Tracer& tracer = pick(f, bvh);
  const std::vector<Ray>& rays = coherent ? f.camera : f.random;
  run_chunks(state, rays.size(), [&](size_t begin, size_t n) {
    Hit hits[64];
    tracer.intersect(std::span<const Ray>(rays.data() + begin, n), std::span<Hit>(hits, n),
                     coherent);
    benchmark::DoNotOptimize(hits);
  });
}

void BM_Occluded(benchmark::State& state, const std::string& spec, bool bvh, bool coherent) {
  Scenes& f = fixture(spec);
  const Tracer& tracer = pick(f, bvh);
  const std::vector<Ray>& rays = coherent ? f.shadow : f.random_cut;
  run_chunks(state, rays.size(), [&](size_t begin, size_t n) {
    uint8_t blocked[64];
    tracer.occluded(std::span<const Ray>(rays.data() + begin, n), std::span<uint8_t>(blocked, n));
    benchmark::DoNotOptimize(blocked);
  });
}

void BM_Build(benchmark::State& state, const std::string& spec, bool bvh) {
  Scenes& f = fixture(spec);
  Tracer& tracer = bvh ? *f.bvh : *f.embree;
  double build_ms = 0.0;
  for (auto _ : state) {
    tracer.rebuild(f.scene);
    build_ms += tracer.stats().build_ms;
  }
  state.counters["build_ms"] = build_ms / double(state.iterations());
  state.counters["memory_MiB"] = double(tracer.stats().memory_bytes) / (1024.0 * 1024.0);
}

#define BOUNCE_BVH_VS_EMBREE(scene_name, spec)                                                   \
  BENCHMARK_CAPTURE(BM_Closest, Embree_random_##scene_name, spec, false, false)->UseRealTime();  \
  BENCHMARK_CAPTURE(BM_Closest, Bvh_random_##scene_name, spec, true, false)->UseRealTime();      \
  BENCHMARK_CAPTURE(BM_Closest, Embree_camera_##scene_name, spec, false, true)->UseRealTime();   \
  BENCHMARK_CAPTURE(BM_Closest, Bvh_camera_##scene_name, spec, true, true)->UseRealTime();       \
  BENCHMARK_CAPTURE(BM_Occluded, Embree_random_##scene_name, spec, false, false)->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_Occluded, Bvh_random_##scene_name, spec, true, false)->UseRealTime();     \
  BENCHMARK_CAPTURE(BM_Occluded, Embree_shadow_##scene_name, spec, false, true)->UseRealTime();  \
  BENCHMARK_CAPTURE(BM_Occluded, Bvh_shadow_##scene_name, spec, true, true)->UseRealTime()

BOUNCE_BVH_VS_EMBREE(cornell, std::string("cornell"));
BOUNCE_BVH_VS_EMBREE(cubes10000, std::string("cubes:10000"));
BENCHMARK_CAPTURE(BM_Build, Embree_cubes10000, std::string("cubes:10000"), false)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Build, Bvh_cubes10000, std::string("cubes:10000"), true)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
