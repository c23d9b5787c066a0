// Ray throughput of our BVH on the GPU (issue 13's target: >= 1 G incoherent rays/s on
// cubes:10000): closest-hit and occlusion queries for a million random rays (origins inside the
// scene's bounds, uniform directions) and for the camera's primary rays at 1920x1080. Timed
// with CUDA events around the kernel alone (rays already on the device).
// Run: build/<preset>/bench/bounce_gpu_microbench
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/gpu/cuda_device.h"
#include "bounce/gpu/device_buffer.h"
#include "bounce/gpu/launch.h"
#include "bounce/scene/load.h"
#include "bounce/trace/bvh.h"
#include "bounce/trace/trace_view.h"

namespace {

using namespace bounce;

struct Fixture {
  Scene scene;
  Bvh bvh;
  DeviceBuffer<BvhNode> nodes;
  DeviceBuffer<BvhTriangle> triangles;
  DeviceBuffer<BvhTriangleId> ids;
  DeviceBuffer<Ray> incoherent, primary;
  DeviceBuffer<Hit> hits;
  DeviceBuffer<uint8_t> blocked;
  TraceView view;
};

Fixture& fixture(const std::string& spec) {
  static std::map<std::string, std::unique_ptr<Fixture>> cache;
  auto& f = cache[spec];
  if (f) return *f;
  f = std::make_unique<Fixture>();
  f->scene = load_scene(spec);
  f->bvh.build(f->scene);
  f->nodes.upload(f->bvh.nodes());
  f->triangles.upload(f->bvh.triangles());
  f->ids.upload(f->bvh.ids());
  f->view.bvh = f->bvh.view();
  f->view.bvh.nodes = f->nodes.data();
  f->view.bvh.triangles = f->triangles.data();
  f->view.bvh.ids = f->ids.data();
  Pcg32 rng(1);
  const vec3 lo = f->scene.bounds.lo, size = f->scene.bounds.hi - f->scene.bounds.lo;
  std::vector<Ray> rays(1 << 20);
  for (Ray& r : rays) {
    r.origin = lo + size * vec3(rng.next_float(), rng.next_float(), rng.next_float());
    r.direction = sample_uniform_sphere(rng.next2());
  }
  f->incoherent.upload(rays);
  const CameraRays cam = CameraRays::from(f->scene.camera, 1920, 1080);
  rays.clear();
  for (int y = 0; y < 1080; ++y)
    for (int x = 0; x < 1920; ++x) {
      Ray r;
      r.origin = cam.origin;
      r.direction = cam.direction(float(x) + 0.5f, float(y) + 0.5f);
      rays.push_back(r);
    }
  f->primary.upload(rays);
  f->hits.resize(rays.size());
  f->blocked.resize(rays.size());
  return *f;
}

// Times `run` (kernel launches) with CUDA events; rays per second as items.
template <typename Run>
void time_kernels(benchmark::State& state, size_t rays, Run&& run) {
  cudaEvent_t begin, end;
  cudaEventCreate(&begin);
  cudaEventCreate(&end);
  run();  // warm-up
  cudaDeviceSynchronize();
  for (auto _ : state) {
    cudaEventRecord(begin);
    run();
    cudaEventRecord(end);
    cudaEventSynchronize(end);
    float ms = 0.0f;
    cudaEventElapsedTime(&ms, begin, end);
    state.SetIterationTime(ms * 1e-3);
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays));
  cudaEventDestroy(begin);
  cudaEventDestroy(end);
}

void BM_GpuClosestHit(benchmark::State& state, const std::string& spec, bool coherent) {
  if (!cuda_device_info().available) {
    state.SkipWithError(("needs a CUDA GPU: " + cuda_device_info().reason).c_str());
    return;
  }
  Fixture& f = fixture(spec);
  const DeviceBuffer<Ray>& rays = coherent ? f.primary : f.incoherent;
  const Ray* r = rays.data();
  Hit* h = f.hits.data();
  const TraceView view = f.view;
  time_kernels(state, rays.size(), [&] {
    launch(rays.size(), [=] __device__(uint32_t i) { h[i] = view.intersect(r[i]); });
  });
}

void BM_GpuOcclusion(benchmark::State& state, const std::string& spec) {
  if (!cuda_device_info().available) {
    state.SkipWithError(("needs a CUDA GPU: " + cuda_device_info().reason).c_str());
    return;
  }
  Fixture& f = fixture(spec);
  const Ray* r = f.incoherent.data();
  uint8_t* b = f.blocked.data();
  const TraceView view = f.view;
  time_kernels(state, f.incoherent.size(), [&] {
    launch(f.incoherent.size(), [=] __device__(uint32_t i) {
      Ray shadow = r[i];
      shadow.tmax = 0.5f;  // shadow rays of a typical length in these scenes
      b[i] = view.occluded(shadow) ? 1 : 0;
    });
  });
}

BENCHMARK_CAPTURE(BM_GpuClosestHit, cubes_incoherent, std::string("cubes:10000"), false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GpuClosestHit, cubes_primary_1080p, std::string("cubes:10000"), true)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GpuOcclusion, cubes_incoherent, std::string("cubes:10000"))
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GpuClosestHit, cornell_incoherent, std::string("cornell"), false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
