// The G-buffer: what primary rays see at each pixel, as a structure of arrays.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"

namespace bounce {

struct GBuffer {
  int width = 0;
  int height = 0;
  std::vector<vec3> position;          // world-space hit point
  std::vector<vec3> normal;            // shading normal, facing the camera
  std::vector<vec3> geometric_normal;  // face normal, facing the camera
  std::vector<vec3> albedo;            // diffuse albedo (texture applied)
  std::vector<float> roughness;        // GGX perceptual roughness
  std::vector<vec3> f0;                // specular reflectance at normal incidence
  // Radiance emitted towards the camera (0 for back faces). A sphere light seen directly is a
  // pixel with emission but no surface (primitive == kNoPrimitive).
  std::vector<vec3> emission;
  std::vector<float> depth;         // distance along the view axis; infinity on a miss
  std::vector<uint32_t> primitive;  // global triangle id (Scene::triangle_offsets), or kNoPrimitive
  std::vector<uint32_t> mesh;       // the object: Scene::meshes index, or kNoPrimitive
  // Weights of the triangle's vertices 1 and 2 at the hit (vertex 0 has 1 - x - y): what
  // interpolates per-vertex data such as light stored at mesh vertices.
  std::vector<vec2> barycentric;
  // Screen-space motion in pixels from where this surface point was in the previous frame to
  // where it is now: compute_motion's, after build_gbuffer (zero from resize until then).
  std::vector<vec2> motion;

  void resize(int w, int h);
  size_t size() const { return size_t(width) * height; }
  bool hit(size_t i) const { return primitive[i] != kNoPrimitive; }
  SurfaceHit surface(size_t i) const { return view().surface(i); }

  GBufferView view() { return view_of<GBufferView>(*this); }
  ConstGBufferView view() const { return view_of<ConstGBufferView>(*this); }

 private:
  // The one list of the arrays, for the writable and the read-only view.
  template <typename View, typename Self>
  static View view_of(Self& g) {
    return {g.position.data(),
            g.normal.data(),
            g.geometric_normal.data(),
            g.albedo.data(),
            g.roughness.data(),
            g.f0.data(),
            g.emission.data(),
            g.depth.data(),
            g.primitive.data(),
            g.mesh.data(),
            g.barycentric.data(),
            g.motion.data(),
            g.width,
            g.height};
  }
};

}  // namespace bounce

#include "bounce/scene/camera.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

class PrimaryRaster;  // primary_raster.h

// Fills the G-buffer (already sized) with one primary ray per pixel through sub-pixel position
// `subpixel` in [0, 1)^2 ((0.5, 0.5) is the centre), all but its motion (compute_motion).
// With `raster` (built for the same camera, sample position and size) each ray's hit comes from
// its pixel's candidate triangle, and only the rays it cannot stand for are traced. Returns the
// number of pixels.
uint64_t build_gbuffer(const SceneView& scene, const Tracer& tracer, const CameraRays& camera,
                       vec2 subpixel, GBuffer& g, const PrimaryRaster* raster = nullptr);
// The pixels of [x0, x1) x [y0, y1) of build_gbuffer's work, on the calling thread, in runs of
// 64 pixels along each row.
void build_gbuffer_block(const SceneView& scene, const Tracer& tracer, const CameraRays& camera,
                         vec2 subpixel, const GBufferView& g, int x0, int y0, int x1, int y1,
                         const PrimaryRaster* raster = nullptr);
// The same from the Scene itself, for callers without a SceneData (tests, benchmarks): copies
// the scene into one first.
uint64_t build_gbuffer(const Scene& scene, const Tracer& tracer, const CameraRays& camera,
                       vec2 subpixel, GBuffer& g);
// Fills the G-buffer's motion from the previous frame's camera and the previous pose of moved
// meshes (motion_kernel.h); `scene` is this frame's.
void compute_motion(const SceneView& scene, const CameraRays& camera, const CameraRays& previous,
                    GBuffer& g);

}  // namespace bounce
