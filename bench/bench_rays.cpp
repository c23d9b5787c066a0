// Ray throughput of the Tracer on the scenes of docs/benchmarks.md at 512x512: primary rays
// (one by one, as a stream flagged incoherent and as a coherent stream) and shadow rays (a
// stream) towards the first light.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/light_sampling.h"
#include "bounce/scene/load.h"
#include "bounce/trace/tracer.h"

namespace {

using namespace bounce;

constexpr int kSize = 512;

struct Fixture {
  Scene scene;
  std::unique_ptr<Tracer> tracer;
  std::vector<Ray> primary;  // in 8x8 tiles, rows of 8
  GBuffer gbuffer;
  std::vector<Ray> shadow;
};

Fixture& fixture(const std::string& spec) {
  static std::map<std::string, std::unique_ptr<Fixture>> cache;
  auto& f = cache[spec];
  if (f) return *f;
  f = std::make_unique<Fixture>();
  f->scene = load_scene(spec);
  f->tracer = make_embree_tracer(f->scene);
  const CameraRays cam = CameraRays::from(f->scene.camera, kSize, kSize);
  for (int ty = 0; ty < kSize; ty += 8)
    for (int tx = 0; tx < kSize; tx += 8)
      for (int y = ty; y < ty + 8; ++y)
        for (int x = tx; x < tx + 8; ++x)
          f->primary.push_back({cam.origin, 0.0f, cam.direction(x + 0.5f, y + 0.5f)});
  f->gbuffer.resize(kSize, kSize);
  build_gbuffer(f->scene, *f->tracer, cam, vec2(0.5f), f->gbuffer);
  // One shadow ray per visible pixel towards a point of the first area light (or light).
  for (size_t i = 0; i < f->gbuffer.size(); ++i) {
    if (!f->gbuffer.hit(i)) continue;
    const vec3 p = f->gbuffer.position[i];
    const LightSample ls =
        !f->scene.area_lights.empty()
            ? sample_area_light(f->scene, f->scene.area_lights[0], p, hammersley(i % 64, 64))
            : sample_punctual_light(f->scene.lights[0], p);
    if (!ls.valid()) continue;
    f->shadow.push_back({offset_origin(p, f->gbuffer.geometric_normal[i]), 0.0f, ls.wi,
                         ls.distance * (1.0f - 1e-4f)});
  }
  return *f;
}

void run_chunks(benchmark::State& state, size_t count, auto&& chunk) {
  for (auto _ : state)
    parallel_for(
        count / 64, [&](size_t c) { chunk(c * 64, 64); }, 16);
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(count));
}

void BM_PrimarySingle(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  run_chunks(state, f.primary.size(), [&](size_t begin, size_t n) {
    Hit hits[64];
    for (size_t k = 0; k < n; ++k) hits[k] = f.tracer->intersect(f.primary[begin + k]);
    benchmark::DoNotOptimize(hits);
  });
}

void BM_PrimaryIncoherentStream(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  run_chunks(state, f.primary.size(), [&](size_t begin, size_t n) {
    Hit hits[64];
    f.tracer->intersect(std::span<const Ray>(f.primary.data() + begin, n), std::span<Hit>(hits, n),
                        false);
    benchmark::DoNotOptimize(hits);
  });
}

void BM_PrimaryStream(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  run_chunks(state, f.primary.size(), [&](size_t begin, size_t n) {
    Hit hits[64];
    f.tracer->intersect(std::span<const Ray>(f.primary.data() + begin, n), std::span<Hit>(hits, n),
                        true);
    benchmark::DoNotOptimize(hits);
  });
}

void BM_Shadow(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  const size_t count = f.shadow.size() / 64 * 64;
  run_chunks(state, count, [&](size_t begin, size_t n) {
    uint8_t blocked[64];
    f.tracer->occluded(std::span<const Ray>(f.shadow.data() + begin, n),
                       std::span<uint8_t>(blocked, n));
    benchmark::DoNotOptimize(blocked);
  });
}

}  // namespace

BENCHMARK_CAPTURE(BM_PrimarySingle, cornell, std::string("cornell"))->UseRealTime();
BENCHMARK_CAPTURE(BM_PrimaryIncoherentStream, cornell, std::string("cornell"))->UseRealTime();
BENCHMARK_CAPTURE(BM_PrimaryStream, cornell, std::string("cornell"))->UseRealTime();
BENCHMARK_CAPTURE(BM_Shadow, cornell, std::string("cornell"))->UseRealTime();
BENCHMARK_CAPTURE(BM_PrimarySingle, cubes10000, std::string("cubes:10000"))->UseRealTime();
BENCHMARK_CAPTURE(BM_PrimaryIncoherentStream, cubes10000, std::string("cubes:10000"))
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_PrimaryStream, cubes10000, std::string("cubes:10000"))->UseRealTime();
BENCHMARK_CAPTURE(BM_Shadow, cubes10000, std::string("cubes:10000"))->UseRealTime();

BENCHMARK_MAIN();
