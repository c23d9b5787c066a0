// PhotonKdTree (the vertex technique's photon map): build time, and the cost of one k-nearest
// query (k = 50, sphere slice on), for photons spread over the faces of the unit cube as photons
// lie on surfaces.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/techniques/vertex/photon_kdtree.h"
#include "bounce/techniques/vertex/vertex_estimate.h"

namespace {

using namespace bounce;

struct Fixture {
  MapPhotons photons;
  std::vector<vec3> queries, normals;
  PhotonKdTree tree;
};

// A point on one of the cube's six faces, and that face's inward normal.
void on_face(Pcg32& rng, vec3& p, vec3& n) {
  const uint32_t face = rng.next_u32() % 6;
  const int axis = int(face % 3);
  p = vec3(rng.next_float(), rng.next_float(), rng.next_float());
  p[axis] = face < 3 ? 0.0f : 1.0f;
  n = vec3(0.0f);
  n[axis] = face < 3 ? 1.0f : -1.0f;
}

Fixture& fixture(size_t n) {
  static std::map<size_t, std::unique_ptr<Fixture>> cache;
  auto& f = cache[n];
  if (f) return *f;
  f = std::make_unique<Fixture>();
  Pcg32 rng(77);
  for (size_t i = 0; i < n; ++i) {
    vec3 p, nn;
    on_face(rng, p, nn);
    f->photons.position.push_back(p);
    f->photons.flux.push_back(vec3(1e-4f));
    f->photons.normal.push_back(nn);
  }
  for (int i = 0; i < 4096; ++i) {
    vec3 p, nn;
    on_face(rng, p, nn);
    f->queries.push_back(p);
    f->normals.push_back(nn);
  }
  f->tree.build(f->photons, 8);
  return *f;
}

void BM_KdTreeBuild(benchmark::State& state) {
  Fixture& f = fixture(size_t(state.range(0)));
  PhotonKdTree tree;
  for (auto _ : state) {
    tree.build(f.photons, 8);
    benchmark::DoNotOptimize(tree.view().position);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * state.range(0));
}
BENCHMARK(BM_KdTreeBuild)->Arg(10000)->Arg(74000)->Arg(500000)->Unit(benchmark::kMillisecond);

void BM_KdTreeQuery(benchmark::State& state) {
  Fixture& f = fixture(size_t(state.range(0)));
  EstimateSettings s;
  s.k = 50;
  s.max_radius = 0.1f;
  s.slice_half = 0.002f;
  KnnHeap heap;
  size_t q = 0;
  for (auto _ : state) {
    const vec3 e = photon_irradiance(f.tree.view(), f.queries[q], f.normals[q], s, heap);
    benchmark::DoNotOptimize(e);
    q = (q + 1) % f.queries.size();
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_KdTreeQuery)->Arg(10000)->Arg(74000)->Arg(500000);

}  // namespace
