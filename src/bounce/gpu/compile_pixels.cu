// nvcc check of the per-pixel kernels: the G-buffer (render/gbuffer_kernel.h) and its motion
// (render/motion_kernel.h), direct light, looped over the lights or resampled, with
// its shadow rays traced at once (render/direct_kernel.h), and the path tracer's pixel and camera
// paths (techniques/path/path_tracer.h).
#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer_kernel.h"
#include "bounce/render/motion_kernel.h"
#include "bounce/scene/camera.h"
#include "bounce/techniques/path/path_tracer.h"

namespace bounce {

__global__ void check_gbuffer(SceneView scene, TraceView trace, CameraRays camera, GBufferView g) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= g.width || y >= g.height) return;
  const Ray ray{camera.origin, 0.0f, camera.direction(float(x) + 0.5f, float(y) + 0.5f)};
  gbuffer_pixel(scene, camera.forward, camera.pixel_spread(), ray, trace.intersect(ray),
                g.index(x, y), g);
}

__global__ void check_motion(SceneView scene, CameraRays camera, CameraRays previous,
                             GBufferView g) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= g.size()) return;
  g.motion[i] = motion_pixel(scene, camera, previous, g, i);
}

__global__ void check_direct(SceneView scene, LightPickerView lights, TraceView trace,
                             ConstGBufferView g, vec3 eye, DirectSettings settings, vec3* out) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= g.size()) return;
  vec3 sum = g.emission[i];
  auto shadow = [&](const Ray& ray, vec3 radiance) {
    if (!trace.occluded(ray)) sum += radiance;
  };
  direct_light_pixel(scene, lights, g, i, eye, settings, shadow);
  out[i] = sum;
}

__global__ void check_path(PathScene ps, PathSettings settings, ConstGBufferView g,
                           CameraRays camera, uint32_t first, int samples, vec3* indirect,
                           vec3* camera_paths, unsigned long long* rays) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= g.size()) return;
  PathCounters counters;
  indirect[i] = path_pixel(ps, settings, g, i, camera.origin, first, samples, 0u, counters);
  Pcg32 rng = path_rng(i, first, 1u);
  const vec3 direction =
      camera.direction(float(i % uint32_t(g.width)), float(i / uint32_t(g.width)));
  camera_paths[i] = ray_radiance(ps, settings, camera.origin, direction, rng, counters);
  atomicAdd(rays, (unsigned long long)counters.rays);
}

}  // namespace bounce
