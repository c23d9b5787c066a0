#include "bounce/render/gbuffer.h"

#include <algorithm>
#include <array>

#include "bounce/core/parallel.h"
#include "bounce/render/gbuffer_kernel.h"
#include "bounce/render/motion_kernel.h"
#include "bounce/render/primary_raster.h"
#include "bounce/scene/scene_data.h"

namespace bounce {

void GBuffer::resize(int w, int h) {
  width = w;
  height = h;
  const size_t n = size();
  position.resize(n);
  normal.resize(n);
  geometric_normal.resize(n);
  albedo.resize(n);
  roughness.resize(n);
  f0.resize(n);
  emission.resize(n);
  depth.resize(n);
  primitive.resize(n);
  mesh.resize(n);
  barycentric.resize(n);
  motion.assign(n, vec2(0.0f));
}

namespace {

constexpr int kGBufferRun = 64;

}  // namespace

// Rays go to the tracer 64 neighbouring pixels of a row at a time: coherent packets, and the
// G-buffer's dozen arrays are written along their rows (in 8 x 8 tiles, a tile row is 96 bytes
// of each array: the writes took twice as long, and the stage about 2.5 ms more on a level at
// 640 x 360; docs/benchmarks.md).
namespace {

// The raster's candidate triangle as the G-buffer reads it, loaded once for the pixels of a run
// that see it (a level at 1280 x 720 has about 200 pixels a triangle).
struct Candidate {
  uint32_t index = PrimaryRaster::kNone;  // in the raster's triangles()
  uint32_t mesh = 0, triangle = 0, id = 0;
  bool cutouts = false;
  // (Value-initialised: GCC cannot see that load() fills them before the first use.)
  SurfaceTriangle surface{};
  TriangleFromOrigin test{};  // for rays from the camera

  void load(const SceneView& scene, const PrimaryRaster& raster, uint32_t c, vec3 eye) {
    const RasterTriangle& r = raster.triangles()[c];
    index = c;
    mesh = r.mesh;
    triangle = r.triangle;
    id = scene.triangle_id(r.mesh, r.triangle);
    surface = surface_triangle(scene, r.mesh, r.triangle);
    cutouts = surface.material->has_cutouts();
    test = TriangleFromOrigin::make(surface.p0, surface.p1, surface.p2, eye);
  }
};

// Pixel i from the raster's candidate, as the traced ray's hit would write it: the ray's hit on
// the candidate (or no triangle where the pixel has none), with the sphere lights. Returns false,
// writing nothing, where the ray must be traced (it misses its candidate, which lies within the
// raster's margin, or the candidate has cut-outs).
bool pixel_from_raster(const SceneView& scene, const TraceView& trace, const PrimaryRaster& raster,
                       vec3 forward, size_t i, const Ray& ray, Candidate& candidate,
                       const GBufferView& g) {
  Hit hit;
  const uint32_t c = raster.candidates()[i];
  if (c == PrimaryRaster::kNone) {
    closest_sphere(trace.spheres, trace.sphere_count, ray, hit);
    gbuffer_pixel(scene, forward, ray, hit, i, g);
    return true;
  }
  if (c != candidate.index) candidate.load(scene, raster, c, ray.origin);
  if (candidate.cutouts) return false;
  if (!candidate.test.intersect(ray.direction, ray.tmin, ray.tmax, hit.t, hit.barycentric))
    return false;
  hit.mesh = candidate.mesh;
  hit.triangle = candidate.triangle;
  closest_sphere(trace.spheres, trace.sphere_count, ray, hit);
  if (hit.valid())
    gbuffer_triangle_pixel(scene, forward, ray, hit, candidate.surface, candidate.id, i, g);
  else
    gbuffer_pixel(scene, forward, ray, hit, i, g);
  return true;
}

}  // namespace

void build_gbuffer_block(const SceneView& scene, const Tracer& tracer, const CameraRays& camera,
                         vec2 subpixel, const GBufferView& g, int x0, int y0, int x1, int y1,
                         const PrimaryRaster* raster) {
  std::array<Ray, kGBufferRun> rays, traced;
  std::array<Hit, kGBufferRun> hits, traced_hits;
  std::array<uint32_t, kGBufferRun> traced_index;
  Candidate candidate;
  const TraceView trace = raster ? tracer.view() : TraceView{};
  for (int y = y0; y < y1; ++y)
    for (int run = x0; run < x1; run += kGBufferRun) {
      const int end = std::min(run + kGBufferRun, x1);
      size_t n = 0;
      for (int x = run; x < end; ++x) {
        Ray& r = rays[n++];
        r.origin = camera.origin;
        r.direction = camera.direction(float(x) + subpixel.x, float(y) + subpixel.y);
        r.tmin = 0.0f;
      }
      if (!raster) {
        tracer.intersect(std::span<const Ray>(rays.data(), n), std::span<Hit>(hits.data(), n),
                         true);
        n = 0;
        for (int x = run; x < end; ++x, ++n)
          gbuffer_pixel(scene, camera.forward, rays[n], hits[n], g.index(x, y), g);
        continue;
      }
      // The pixels the raster stands for written at once, the rays it cannot stand for traced
      // together.
      size_t m = 0;
      for (size_t k = 0; k < n; ++k)
        if (!pixel_from_raster(scene, trace, *raster, camera.forward, g.index(run + int(k), y),
                               rays[k], candidate, g)) {
          traced[m] = rays[k];
          traced_index[m++] = uint32_t(k);
        }
      if (m == 0) continue;
      tracer.intersect(std::span<const Ray>(traced.data(), m),
                       std::span<Hit>(traced_hits.data(), m), true);
      for (size_t k = 0; k < m; ++k)
        gbuffer_pixel(scene, camera.forward, traced[k], traced_hits[k],
                      g.index(run + int(traced_index[k]), y), g);
    }
}

uint64_t build_gbuffer(const SceneView& scene, const Tracer& tracer, const CameraRays& camera,
                       vec2 subpixel, GBuffer& g, const PrimaryRaster* raster) {
  const GBufferView view = g.view();
  parallel_for_tiles(g.width, g.height, kGBufferRun, 1, [&](int x0, int y0, int x1, int y1) {
    build_gbuffer_block(scene, tracer, camera, subpixel, view, x0, y0, x1, y1, raster);
  });
  return uint64_t(g.width) * g.height;
}

namespace {

// Row y of the motion when only the camera moved, in a loop the compiler vectorises (with copies
// of its inputs, which its stores then cannot change).
void camera_motion_row(const CameraRays& current, const CameraRays& previous,
                       const ConstGBufferView& g, vec2* motion, int y) {
  const CameraRays now = current, before = previous;
  const ConstGBufferView gv = g;
  const size_t first = size_t(y) * size_t(gv.width);
  BOUNCE_IVDEP
  for (int x = 0; x < gv.width; ++x)
    motion[first + size_t(x)] = camera_motion_pixel(now, before, gv, first + size_t(x), x, y);
}

}  // namespace

void compute_motion(const SceneView& scene, const CameraRays& camera, const CameraRays& previous,
                    GBuffer& g) {
  bool meshes_moved = false;
  for (uint32_t m = 0; m < scene.mesh_count && !meshes_moved; ++m)
    meshes_moved = scene.meshes[m].previous_positions != nullptr;
  // A still camera over meshes without a previous pose moves no pixel: zero, as motion_pixel
  // would give (primary rays hit only in front of the camera), without its pass over the
  // G-buffer's positions and ids.
  if (!meshes_moved && camera == previous) {
    std::fill(g.motion.begin(), g.motion.end(), vec2(0.0f));
    return;
  }
  const GBufferView view = g.view();
  const ConstGBufferView read = view;
  if (!meshes_moved) {
    // Only the camera moved (the walk, the viewer's fly camera): row loops the compiler
    // vectorises.
    parallel_for(
        size_t(g.height),
        [&](size_t row) { camera_motion_row(camera, previous, read, view.motion, int(row)); }, 2);
    return;
  }
  parallel_for(
      g.size(), [&](size_t i) { view.motion[i] = motion_pixel(scene, camera, previous, read, i); },
      4096);
}

uint64_t build_gbuffer(const Scene& scene, const Tracer& tracer, const CameraRays& camera,
                       vec2 subpixel, GBuffer& g) {
  const SceneData data = SceneData::from(scene);
  return build_gbuffer(data.view(), tracer, camera, subpixel, g);
}

}  // namespace bounce
