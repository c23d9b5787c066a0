// The G-buffer's per-pixel kernel: what one primary ray's hit leaves in the G-buffer. The CPU
// launcher (gbuffer.cpp) traces the rays in coherent streams and calls this for each pixel; a
// GPU launcher traces with the trace view and calls the same body.
#pragma once

#include <cstddef>
#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

// Writes pixel i for a primary ray along unit `ray.direction` that met triangle `hit`
// (hit.valid()), whose surface_triangle is `t` and global id `id`: what gbuffer_pixel writes there.
// The raster's runs load `t` once for the pixels that see the same triangle; kForm: what the
// caller knows of it (SurfaceForm). `spread`: the angle a pixel spans (CameraRays::pixel_spread);
// textures are filtered over the pixel's footprint (surface_on's kFiltered), as the reference's
// many samples per pixel average them. 0: read at the point.
template <SurfaceForm kForm = SurfaceForm{}>
BOUNCE_HD BOUNCE_LANE_INLINE void gbuffer_triangle_pixel(const SceneView& scene, vec3 forward,
                                                         float spread, const Ray& ray,
                                                         const Hit& hit, const SurfaceTriangle& t,
                                                         uint32_t id, size_t i,
                                                         const GBufferView& g) {
  g.store(i, surface_on<false, kForm, true>(t, hit.barycentric, ray.direction, scene.textures,
                                            hit.t * spread));
  g.primitive[i] = id;
  g.mesh[i] = hit.mesh;
  g.barycentric[i] = hit.barycentric;
  g.depth[i] = hit.t * glm::dot(ray.direction, forward);
}

// Writes pixel i for a primary ray along unit `ray.direction` that met `hit` (a triangle, a
// sphere light, or nothing). `forward` is the camera's viewing axis: depth is measured along it.
// Every field but the motion, which the motion pass (motion_kernel.h) writes for every pixel
// after this one: written here too, it was 8 of the 104 bytes a pixel stores for nothing.
BOUNCE_HD inline void gbuffer_pixel(const SceneView& scene, vec3 forward, float spread,
                                    const Ray& ray, const Hit& hit, size_t i,
                                    const GBufferView& g) {
  if (!hit.valid()) {
    g.primitive[i] = g.mesh[i] = kNoPrimitive;
    g.barycentric[i] = vec2(0.0f);
    g.depth[i] = std::numeric_limits<float>::infinity();
    SurfaceHit none;
    none.normal = none.geometric_normal = vec3(0.0f);
    // A sphere light in front shows its radiance; it has no surface to shade. Past all
    // geometry the ray sees the environment (black without one).
    if (hit.sphere_light()) {
      none.emission = scene.lights[hit.light].radiance;
      g.depth[i] = hit.t * glm::dot(ray.direction, forward);
    } else {
      none.emission = scene.background(ray.direction);
    }
    g.store(i, none);
    return;
  }
  gbuffer_triangle_pixel(scene, forward, spread, ray, hit,
                         surface_triangle(scene, hit.mesh, hit.triangle),
                         scene.triangle_id(hit.mesh, hit.triangle), i, g);
}

}  // namespace bounce
