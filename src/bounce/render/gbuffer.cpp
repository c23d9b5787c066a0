#include "bounce/render/gbuffer.h"

#include <algorithm>
#include <array>
#include <iterator>

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
  SurfaceForm form;  // the triangle's, for the spans' loops (span_of_form)
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
    form = SurfaceForm::of(surface);
    test = TriangleFromOrigin::make(surface.p0, surface.p1, surface.p2, eye);
  }
};

// Pixel i from the raster's candidate, as the traced ray's hit would write it: the ray's hit on
// the candidate (or no triangle where the pixel has none), with the sphere lights. Returns false,
// writing nothing, where the ray must be traced (it misses its candidate, which lies within the
// raster's margin, or the candidate has cut-outs).
bool pixel_from_raster(const SceneView& scene, const TraceView& trace, const PrimaryRaster& raster,
                       vec3 forward, float spread, size_t i, const Ray& ray, Candidate& candidate,
                       const GBufferView& g) {
  Hit hit;
  const uint32_t c = raster.candidates()[i];
  if (c == PrimaryRaster::kNone) {
    closest_sphere(trace.spheres, trace.sphere_count, ray, hit);
    gbuffer_pixel(scene, forward, spread, ray, hit, i, g);
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
    gbuffer_triangle_pixel(scene, forward, spread, ray, hit, candidate.surface, candidate.id, i, g);
  else
    gbuffer_pixel(scene, forward, spread, ray, hit, i, g);
  return true;
}

// Pixel x0 + k of row y (G-buffer index i0 + k) from the raster's candidate `c` as
// pixel_from_raster writes it where the camera ray meets `c`; whether it misses, in which case
// what it wrote must be written again (the ray traced). No branch: lanes of a loop.
template <SurfaceForm kForm>
BOUNCE_LANE_INLINE bool candidate_pixel(const SceneView& scene, const CameraRays& camera,
                                        vec2 subpixel, int x0, int y, size_t k, size_t i0,
                                        const Candidate& c, const GBufferView& g) {
  Ray ray;
  ray.origin = camera.origin;
  ray.direction = camera.direction(float(x0 + int(k)) + subpixel.x, float(y) + subpixel.y);
  ray.tmin = 0.0f;
  Hit hit;
  hit.mesh = c.mesh;
  hit.triangle = c.triangle;
  const bool meets = c.test.meets(ray.direction, ray.tmin, ray.tmax, hit.t, hit.barycentric);
  gbuffer_triangle_pixel<kForm>(scene, camera.forward, camera.pixel_spread(), ray, hit, c.surface,
                                c.id, i0 + k, g);
  return !meets;
}

constexpr size_t kSpanLanes = 8;

// Pixels [k0, k1) of a run of n pixels, whose rays all have `candidate` (no cut-outs) in a scene
// without sphere lights, kForm being the candidate's form: written by candidate_pixel in a loop
// GCC vectorises eight lanes wide (the triangle's data, its material and kForm the same in every
// lane; `missed` of 32 bits, as wide as a float, for eight lanes a vector), `missed` marking the
// rays to trace. The loop runs over whole blocks of eight (over the span itself it ran scalar
// below 32 pixels, and most spans are shorter): a block that reaches past k1 writes pixels of
// the run's later spans too, which those then overwrite; the run's last pixels go one by one.
// Out of line, so that the loop is compiled on its own.
template <SurfaceForm kForm>
[[gnu::noinline]] void span_from_raster(const SceneView& scene, const CameraRays& camera,
                                        vec2 subpixel, int x0, int y, size_t k0, size_t k1,
                                        size_t n, size_t i0, const Candidate& candidate,
                                        const GBufferView& g, uint32_t* missed) {
  const SceneView sv = scene;  // copies: the loop's stores cannot change them
  const CameraRays cam = camera;
  Candidate c = candidate;
  const MaterialRecord material = *c.surface.material;  // (the loop then loads none of it)
  c.surface.material = &material;
  const GBufferView gv = g;
  // Whole blocks of eight from k0 up to k1, within the run.
  const size_t blocks = std::min(k1 - k0 + kSpanLanes - 1, n - k0) / kSpanLanes;
  const size_t count = blocks * kSpanLanes;
  if (count % kSpanLanes != 0) __builtin_unreachable();  // (GCC: then no scalar epilogue)
  BOUNCE_IVDEP
  for (size_t j = 0; j < count; ++j)
    missed[k0 + j] = uint32_t(candidate_pixel<kForm>(sv, cam, subpixel, x0, y, k0 + j, i0, c, gv));
  for (size_t k = k0 + count; k < k1; ++k)
    missed[k] = uint32_t(candidate_pixel<kForm>(sv, cam, subpixel, x0, y, k, i0, c, gv));
}

// The forms (SurfaceForm) whose spans have a loop of their own, without a branch. Any other form
// takes the loop that reads the triangle's.
constexpr MaterialForm kUntextured{.known = true};
constexpr MaterialForm kAlbedoTexture{.known = true, .albedo_texture = true};
constexpr SurfaceForm kSpanForms[] = {
    // A Quake level's surfaces, some glowing through an emission texture.
    {.known = true, .normals = true, .uvs = true, .material = kAlbedoTexture},
    {.known = true,
     .normals = true,
     .uvs = true,
     .material = {.known = true, .albedo_texture = true, .emission_texture = true}},
    // OBJ's, untextured: with or without texture coordinates and normals (the Cornell box).
    {.known = true, .normals = true, .uvs = true, .material = kUntextured},
    {.known = true, .normals = true, .material = kUntextured},
    {.known = true, .material = kUntextured},
    // glTF's metallic ones without a normal map.
    {.known = true,
     .normals = true,
     .uvs = true,
     .material =
         {.known = true, .albedo_texture = true, .metallic = true, .metal_rough_texture = true}},
    {.known = true, .normals = true, .uvs = true, .material = {.known = true, .metallic = true}},
};

// span_from_raster with the candidate's form, from kSpanForms[I] on.
template <size_t I = 0>
void span_of_form(SurfaceForm form, const SceneView& scene, const CameraRays& camera, vec2 subpixel,
                  int x0, int y, size_t k0, size_t k1, size_t n, size_t i0,
                  const Candidate& candidate, const GBufferView& g, uint32_t* missed) {
  if constexpr (I == std::size(kSpanForms)) {
    span_from_raster<SurfaceForm{}>(scene, camera, subpixel, x0, y, k0, k1, n, i0, candidate, g,
                                    missed);
  } else if (form == kSpanForms[I]) {
    span_from_raster<kSpanForms[I]>(scene, camera, subpixel, x0, y, k0, k1, n, i0, candidate, g,
                                    missed);
  } else {
    span_of_form<I + 1>(form, scene, camera, subpixel, x0, y, k0, k1, n, i0, candidate, g, missed);
  }
}

}  // namespace

void build_gbuffer_block(const SceneView& scene, const Tracer& tracer, const CameraRays& camera,
                         vec2 subpixel, const GBufferView& g, int x0, int y0, int x1, int y1,
                         const PrimaryRaster* raster) {
  std::array<Ray, kGBufferRun> rays, traced;
  std::array<Hit, kGBufferRun> hits, traced_hits;
  std::array<uint32_t, kGBufferRun> traced_index;
  std::array<uint32_t, kGBufferRun> missed;
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
          gbuffer_pixel(scene, camera.forward, camera.pixel_spread(), rays[n], hits[n],
                        g.index(x, y), g);
        continue;
      }
      // The pixels the raster stands for written at once, the rays it cannot stand for traced
      // together.
      size_t m = 0;
      const size_t i0 = g.index(run, y);
      const uint32_t* candidates = raster->candidates() + i0;
      for (size_t k = 0; k < n;) {
        // The pixels from k on that share its candidate.
        size_t end = k + 1;
        while (end < n && candidates[end] == candidates[k]) ++end;
        const uint32_t c = candidates[k];
        if (c != PrimaryRaster::kNone && trace.sphere_count == 0) {
          if (c != candidate.index) candidate.load(scene, *raster, c, camera.origin);
          if (!candidate.cutouts) {
            span_of_form(candidate.form, scene, camera, subpixel, run, y, k, end, n, i0, candidate,
                         g, missed.data());
            for (; k < end; ++k)
              if (missed[k]) {
                traced[m] = rays[k];
                traced_index[m++] = uint32_t(k);
              }
            continue;
          }
        }
        for (; k < end; ++k)
          if (!pixel_from_raster(scene, trace, *raster, camera.forward, camera.pixel_spread(),
                                 i0 + k, rays[k], candidate, g)) {
            traced[m] = rays[k];
            traced_index[m++] = uint32_t(k);
          }
      }
      if (m == 0) continue;
      tracer.intersect(std::span<const Ray>(traced.data(), m),
                       std::span<Hit>(traced_hits.data(), m), true);
      for (size_t k = 0; k < m; ++k)
        gbuffer_pixel(scene, camera.forward, camera.pixel_spread(), traced[k], traced_hits[k],
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
