// PhotonHashGrid: build time and gather throughput for uniform points in the unit cube, with the
// radius chosen so that a gather holds ~30 points (queries stay a radius away from the faces).
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/core/rng.h"
#include "bounce/render/photon_hash_grid.h"

namespace {

using namespace bounce;

constexpr float kPointsPerGather = 30.0f;
constexpr size_t kQueries = 1 << 14;

struct Fixture {
  std::vector<vec3> points;
  std::vector<vec3> flux;  // a payload read by index, as the density estimate reads photons
  std::vector<vec3> queries;
  float radius = 0.0f;
  PhotonHashGrid grid;
};

Fixture& fixture(size_t n) {
  static std::map<size_t, std::unique_ptr<Fixture>> cache;
  auto& f = cache[n];
  if (f) return *f;
  f = std::make_unique<Fixture>();
  // n * 4/3 pi r^3 = kPointsPerGather.
  f->radius = std::cbrt(kPointsPerGather * 3.0f / (4.0f * kPi * float(n)));
  Pcg32 rng(1234);
  f->points.resize(n);
  for (vec3& p : f->points) p = vec3(rng.next_float(), rng.next_float(), rng.next_float());
  f->flux.resize(n);
  for (vec3& p : f->flux) p = vec3(rng.next_float(), rng.next_float(), rng.next_float());
  f->queries.resize(kQueries);
  for (vec3& q : f->queries)
    q = vec3(f->radius) +
        (1.0f - 2.0f * f->radius) * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  f->grid.build(f->points, f->radius);
  return *f;
}

void BM_HashGridBuild(benchmark::State& state) {
  Fixture& f = fixture(size_t(state.range(0)));
  PhotonHashGrid grid;  // reused, as a renderer rebuilding per frame would
  for (auto _ : state) {
    grid.build(f.points, f.radius);
    benchmark::DoNotOptimize(grid.cell_start().data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t(f.points.size()));
  state.counters["radius"] = f.radius;
}

// Gathers on one thread that sum the flux of the points found (the shape of a density
// estimate: a payload read by index for each hit).
void BM_HashGridQuery(benchmark::State& state) {
  Fixture& f = fixture(size_t(state.range(0)));
  const vec3* flux = f.flux.data();
  uint64_t found = 0;
  for (auto _ : state) {
    for (const vec3& q : f.queries) {
      vec3 sum(0.0f);
      uint32_t n = 0;
      f.grid.for_each_within(q, f.radius, [&](uint32_t i) {
        sum += flux[i];
        ++n;
      });
      benchmark::DoNotOptimize(sum);
      found += n;
    }
  }
  state.SetItemsProcessed(state.iterations() * int64_t(f.queries.size()));
  state.counters["found/query"] = double(found) / double(state.iterations() * f.queries.size());
}

// The same gathers through parallel_for (a kernel over queries), with 1 or 2 worker threads.
void BM_HashGridQueryParallel(benchmark::State& state) {
  Fixture& f = fixture(size_t(state.range(0)));
  ThreadLimit limit(int(state.range(1)));
  const PhotonHashGridView view = f.grid.view();
  const float radius = f.radius;
  const vec3* queries = f.queries.data();
  const vec3* flux = f.flux.data();
  std::vector<vec3> out(f.queries.size());
  vec3* sums = out.data();
  for (auto _ : state) {
    parallel_for(
        f.queries.size(),
        [=](size_t k) {
          vec3 sum(0.0f);
          view.for_each_within(queries[k], radius, [&](uint32_t i) { sum += flux[i]; });
          sums[k] = sum;
        },
        64);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t(f.queries.size()));
}

BENCHMARK(BM_HashGridBuild)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HashGridQuery)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HashGridQueryParallel)
    ->ArgsProduct({{1000, 10000, 100000, 1000000}, {1, 2}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

}  // namespace
