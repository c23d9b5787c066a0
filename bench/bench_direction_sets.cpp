// The direction sets of the layered hit buffers (seed 001 section 3.2): the nearest-direction
// lookup's speed, with each set's quality as counters (worst and mean angular error in degrees,
// spread of the cells' solid angles). docs/lhb.md quotes the table.
// Run: build/release/bench/bounce_microbench --benchmark_filter=DirectionSet
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "bounce/techniques/lhb/direction_sets.h"

namespace bounce {
namespace {

DirectionSet set_for(int index) {
  switch (index) {
    case 0:
      return DirectionSet::octahedron(0);
    case 1:
      return DirectionSet::octahedron(1);
    case 2:
      return DirectionSet::octahedron(2);
    case 3:
      return DirectionSet::icosahedron(0);
    case 4:
      return DirectionSet::icosahedron(1);
    case 5:
      return DirectionSet::icosahedron(2);
    case 6:
      return DirectionSet::halton(144);
    case 7:
      return DirectionSet::halton(256);
    case 8:
      return DirectionSet::halton(320);
    case 9:
      return DirectionSet::tetrahedron(0);
    case 10:
      return DirectionSet::tetrahedron(1);
    case 11:
      return DirectionSet::tetrahedron(2);
    case 12:
      return DirectionSet::tetrahedron(3);
    case 13:
      return DirectionSet::uv_grid(4);
    case 14:
      return DirectionSet::uv_grid(8);
    default:
      return DirectionSet::uv_grid(9);
  }
}

void BM_DirectionSetLookup(benchmark::State& state) {
  const DirectionSet set = set_for(int(state.range(0)));
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  std::vector<vec3> queries(4096);
  for (vec3& q : queries) q = glm::normalize(vec3(g(rng), g(rng), g(rng)));
  const DirectionSetView view = set.view();
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(view.nearest(queries[k]));
    k = (k + 1) & 4095;
  }
  const DirectionSetQuality q = evaluate_direction_set(set, 1 << 20);
  state.SetLabel(set.name());
  state.counters["worst_deg"] = q.worst_error_deg;
  state.counters["mean_deg"] = q.mean_error_deg;
  state.counters["area_cv"] = q.cell_area_cv;
  state.counters["area_max/min"] = q.cell_area_ratio;
  state.counters["candidates_max"] = set.max_candidates();
}
BENCHMARK(BM_DirectionSetLookup)->DenseRange(0, 15);

}  // namespace
}  // namespace bounce
