// Seed 001 table 6.5 on this machine: closest-hit queries through the layered hit buffers against
// Embree on the same incoherent rays, and the buffers' build cost (the static scene once; a
// 100K-triangle moving mesh per frame). 320 icosahedron directions, 128 x 128, 16 layers.
//
// Rays: from points spread over the scene's triangles (offset along the normal), directions
// cosine-distributed about the normal. "Snapped" rays go along the nearest buffer direction, so
// Embree and the buffers answer exactly the same ray; "free" rays keep their own direction, which
// the buffers snap (the lookup is inside the timing). Counters: the visibility error against
// Embree on the same rays (differ = fraction of queries whose triangle differs, depth_err = mean
// |t difference| over queries both hit, in texels), memory and build time.
//
// Run: build/release/bench/bounce_microbench --benchmark_filter=Lhb
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/core/timer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/lhb/direction_sets.h"
#include "bounce/techniques/lhb/layered_hit_buffers.h"
#include "bounce/techniques/lhb/lhb_query.h"
#include "bounce/trace/tracer.h"

namespace {

using namespace bounce;

constexpr int kRays = 1 << 20;

// A high-polygon stand-in for the seed's statues: a sphere of 2 r^2 triangles whose radius is
// displaced by a few sines, in a room (so rays that leave it hit something).
Mesh bumpy_sphere(int r, vec3 centre, float radius) {
  Mesh m;
  m.name = "bumpy sphere";
  for (int i = 0; i <= r; ++i)
    for (int j = 0; j <= r; ++j) {
      const float theta = kPi * float(i) / float(r), phi = 2.0f * kPi * float(j) / float(r);
      const float bump = 1.0f + 0.12f * std::sin(7.0f * theta) * std::sin(5.0f * phi) +
                         0.05f * std::sin(23.0f * theta + 3.0f * phi);
      m.positions.push_back(centre + radius * bump *
                                         vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                              std::sin(theta) * std::sin(phi)));
    }
  const auto at = [&](int i, int j) { return uint32_t(i * (r + 1) + j); };
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < r; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  m.materials.assign(m.triangles.size(), 2);
  return m;
}

// cubes:1's room and light around a bumpy sphere of about `triangles` triangles.
Scene statue(int triangles) {
  Scene s = make_cubes(1);
  s.meshes.pop_back();  // the one cube
  s.meshes.push_back(bumpy_sphere(int(std::sqrt(triangles / 2.0)), vec3(0, 2.5f, 0), 2.0f));
  s.source = "statue";
  s.finalize();
  return s;
}

Scene scene_for(const std::string& spec) {
  return spec.rfind("statue:", 0) == 0 ? statue(std::stoi(spec.substr(7))) : load_scene(spec);
}

struct Fixture {
  std::string spec;
  Scene scene;
  std::unique_ptr<Tracer> embree;
  DirectionSet directions = DirectionSet::icosahedron(2);
  LayeredHitBuffers lhb;
  double build_ms = 0.0;
  std::vector<Ray> snapped, free;
  std::vector<int> snapped_dir;
  std::vector<uint32_t> origin_prim;
};

// One scene at a time: each holds hundreds of megabytes of buffers.
Fixture& fixture(const std::string& spec) {
  static std::unique_ptr<Fixture> f;
  if (f && f->spec == spec) return *f;
  f.reset();
  f = std::make_unique<Fixture>();
  f->spec = spec;
  f->scene = scene_for(spec);
  f->embree = make_embree_tracer(f->scene);
  const Stopwatch watch;
  f->lhb.build(f->scene, f->directions.directions(), LhbSettings{});
  f->build_ms = watch.elapsed_ms();
  Pcg32 rng(5);
  const Scene& s = f->scene;
  while (f->free.size() < kRays) {
    const uint32_t m = rng.next_below(uint32_t(s.meshes.size()));
    const Mesh& mesh = s.meshes[m];
    const uint32_t t = rng.next_below(uint32_t(mesh.triangles.size()));
    const vec3 n_area = mesh.face_normal_area2(t);
    if (!(glm::length(n_area) > 0.0f)) continue;
    const vec3 n = glm::normalize(n_area);
    vec2 b = rng.next2();
    if (b.x + b.y > 1.0f) b = vec2(1.0f) - b;
    const uvec3 i = mesh.triangles[t];
    const vec3 p = mesh.positions[i.x] + b.x * (mesh.positions[i.y] - mesh.positions[i.x]) +
                   b.y * (mesh.positions[i.z] - mesh.positions[i.x]);
    const vec3 w = Basis::from_normal(n).to_world(sample_cosine_hemisphere(rng.next2()));
    const int d = f->directions.nearest(w);
    const vec3 o = offset_origin(p, n);
    f->free.push_back({o, 0.0f, w});
    f->snapped.push_back({o, 0.0f, f->directions.directions()[size_t(d)]});
    f->snapped_dir.push_back(d);
    f->origin_prim.push_back(s.triangle_offsets[m] + t);
  }
  return *f;
}

uint32_t global_id(const Scene& s, const Hit& h) {
  return h.valid() ? s.triangle_offsets[h.mesh] + h.triangle : LhbHit::kNone;
}

void report(benchmark::State& state, const Fixture& f) {
  state.SetItemsProcessed(int64_t(state.iterations()) * kRays);
  const LhbStats st = f.lhb.stats();
  state.counters["triangles"] = double(f.scene.triangle_count());
  state.counters["build_ms"] = f.build_ms;
  state.counters["MiB"] = double(st.memory_bytes) / (1024.0 * 1024.0);
  state.counters["overflow_texels"] = double(st.overflow_texels);
}

// The visibility error of the buffers against Embree on `rays` (Embree traces each exactly).
void visibility_error(benchmark::State& state, const Fixture& f, const std::vector<Ray>& rays) {
  const LhbView view = f.lhb.view();
  std::vector<uint8_t> differ(rays.size());
  std::vector<float> depth_err(rays.size());
  parallel_for(rays.size(), [&](size_t k) {
    const Hit want = f.embree->intersect(rays[k]);
    const int d = f.snapped_dir[k];
    const LhbHit got = lhb_closest(view, d, rays[k].origin, 0.0f, vec2(0.0f), f.origin_prim[k]);
    differ[k] = got.prim != global_id(f.scene, want);
    depth_err[k] =
        got.valid() && want.valid() ? std::abs(got.t - want.t) / f.lhb.texel_size(d) : -1.0f;
  });
  double n_differ = 0, sum = 0, both = 0;
  for (size_t k = 0; k < rays.size(); ++k) {
    n_differ += differ[k];
    if (depth_err[k] >= 0) sum += depth_err[k], ++both;
  }
  state.counters["differ"] = n_differ / double(rays.size());
  state.counters["depth_err_texels"] = sum / std::max(both, 1.0);
}

void BM_LhbSnapped(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  const LhbView view = f.lhb.view();
  for (auto _ : state)
    parallel_for(
        kRays / 64,
        [&](size_t c) {
          for (size_t k = c * 64; k < c * 64 + 64; ++k) {
            const LhbHit h = lhb_closest(view, f.snapped_dir[k], f.snapped[k].origin, 0.0f,
                                         vec2(0.0f), f.origin_prim[k]);
            benchmark::DoNotOptimize(h);
          }
        },
        16);
  report(state, f);
  visibility_error(state, f, f.snapped);
}

void BM_LhbFree(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  const LhbView view = f.lhb.view();
  const DirectionSetView set = f.directions.view();
  for (auto _ : state)
    parallel_for(
        kRays / 64,
        [&](size_t c) {
          for (size_t k = c * 64; k < c * 64 + 64; ++k) {
            const int d = set.nearest(f.free[k].direction);
            const LhbHit h =
                lhb_closest(view, d, f.free[k].origin, 0.0f, vec2(0.0f), f.origin_prim[k]);
            benchmark::DoNotOptimize(h);
          }
        },
        16);
  report(state, f);
  visibility_error(state, f, f.free);
}

void BM_EmbreeSnapped(benchmark::State& state, const std::string& spec) {
  Fixture& f = fixture(spec);
  for (auto _ : state)
    parallel_for(
        kRays / 64,
        [&](size_t c) {
          Hit hits[64];
          f.embree->intersect(std::span<const Ray>(f.snapped.data() + c * 64, 64),
                              std::span<Hit>(hits, 64), false);
          benchmark::DoNotOptimize(hits);
        },
        16);
  report(state, f);
}

// A moving mesh of about 100K triangles in cubes:1's room, for 320 directions at 128 x 128, as
// keyframes move it: a turn about its centre and a slide, posed from its first positions each
// frame. `instances` 1: the mesh is an instance, re-posed by the fitted transform (the default);
// 0: the seed's way, its slab rasterized again every frame.
void BM_LhbMovingMeshRebuild(benchmark::State& state) {
  Scene s = make_cubes(1);
  s.meshes.pop_back();
  const vec3 centre(0, 2.5f, 0);
  s.meshes.push_back(bumpy_sphere(224, centre, 1.5f));
  s.finalize();
  const uint32_t moving = uint32_t(s.meshes.size() - 1);
  const std::vector<vec3> rest = s.meshes[moving].positions;
  const DirectionSet directions = DirectionSet::icosahedron(2);
  LhbSettings settings;
  if (state.range(0) == 0) settings.max_instances = 0;
  LayeredHitBuffers lhb;
  const Stopwatch build_watch;
  lhb.build(s, directions.directions(), settings, std::vector<uint32_t>{moving});
  // The build's moving part: the instance's capture, or the slab's first rasterization.
  state.counters["first_build_moving_ms"] = build_watch.elapsed_ms() - lhb.stats().static_build_ms;
  SceneChange change;
  change.moved_meshes = {moving};
  int frame = 0;
  for (auto _ : state) {
    state.PauseTiming();
    ++frame;
    const float angle = 0.05f * float(frame), slide = 0.3f * std::sin(0.1f * float(frame));
    const float c = std::cos(angle), sn = std::sin(angle);
    for (size_t i = 0; i < rest.size(); ++i) {
      const vec3 r = rest[i] - centre;
      s.meshes[moving].positions[i] =
          centre + vec3(c * r.x + sn * r.z + slide, r.y, -sn * r.x + c * r.z);
    }
    s.derive();
    state.ResumeTiming();
    lhb.update(s, change);
  }
  const LhbStats st = lhb.stats();
  state.counters["moving_triangles"] = double(st.dynamic_triangles + st.instance_triangles);
  state.counters["instances"] = double(st.instances);
  // Texels per side of the instance's buffers.
  state.counters["instance_side"] =
      st.instances ? std::sqrt(double(st.instance_texels) / double(st.directions)) : 0.0;
  state.counters["rasterized"] = double(st.dynamic_builds + st.instance_captures);
  state.counters["static_builds"] = double(st.static_builds);
  state.counters["MiB"] = double(st.memory_bytes) / (1024.0 * 1024.0);
}

}  // namespace

#define BOUNCE_LHB_SCENE(name, spec)                                        \
  BENCHMARK_CAPTURE(BM_LhbSnapped, name, std::string(spec))->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_LhbFree, name, std::string(spec))->UseRealTime();    \
  BENCHMARK_CAPTURE(BM_EmbreeSnapped, name, std::string(spec))->UseRealTime();

BOUNCE_LHB_SCENE(cornell, "cornell")
BOUNCE_LHB_SCENE(cubes1000, "cubes:1000")
BOUNCE_LHB_SCENE(cubes10000, "cubes:10000")
BOUNCE_LHB_SCENE(cubes83334, "cubes:83334")
BOUNCE_LHB_SCENE(statue1M, "statue:1000000")
BENCHMARK(BM_LhbMovingMeshRebuild)
    ->ArgName("instances")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
