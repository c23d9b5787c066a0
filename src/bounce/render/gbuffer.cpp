#include "bounce/render/gbuffer.h"

#include <array>

#include "bounce/core/parallel.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/surface.h"

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

static void write_gbuffer_pixel(const Scene& scene, const CameraRays& camera, const Ray& ray,
                                const Hit& hit, size_t i, GBuffer& g) {
  const SphereLightHit light = intersect_sphere_lights(scene, ray.origin, ray.direction, hit.t);
  if (!hit.valid() || light.light >= 0) {
    g.primitive[i] = g.mesh[i] = kNoPrimitive;
    g.barycentric[i] = vec2(0.0f);
    g.depth[i] = std::numeric_limits<float>::infinity();
    g.position[i] = g.normal[i] = g.geometric_normal[i] = vec3(0.0f);
    g.albedo[i] = g.f0[i] = g.emission[i] = vec3(0.0f);
    g.roughness[i] = 1.0f;
    // A sphere light in front shows its radiance; it has no surface to shade.
    if (light.light >= 0) {
      g.emission[i] = scene.lights[light.light].radiance;
      g.depth[i] = light.t * glm::dot(ray.direction, camera.forward);
    }
    return;
  }
  const SurfaceHit s = surface_at(scene, hit, ray.direction);
  g.primitive[i] = scene.triangle_offsets[hit.mesh] + hit.triangle;
  g.mesh[i] = hit.mesh;
  g.barycentric[i] = hit.barycentric;
  g.position[i] = s.position;
  g.normal[i] = s.normal;
  g.geometric_normal[i] = s.geometric_normal;
  g.albedo[i] = s.albedo;
  g.roughness[i] = s.roughness;
  g.f0[i] = s.f0;
  g.emission[i] = s.emission;
  g.depth[i] = hit.t * glm::dot(ray.direction, camera.forward);
}

uint64_t build_gbuffer(const Scene& scene, const Tracer& tracer, const CameraRays& camera,
                       vec2 subpixel, GBuffer& g) {
  constexpr int kTile = 8;
  // Rays go to the tracer in rows of 8 pixels: the packets it traces are as coherent as possible.
  parallel_for_tiles(g.width, g.height, kTile, [&](int x0, int y0, int x1, int y1) {
    std::array<Ray, kTile * kTile> rays;
    std::array<Hit, kTile * kTile> hits;
    size_t n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        Ray& r = rays[n++];
        r.origin = camera.origin;
        r.direction = camera.direction(float(x) + subpixel.x, float(y) + subpixel.y);
        r.tmin = 0.0f;
      }
    tracer.intersect(std::span<const Ray>(rays.data(), n), std::span<Hit>(hits.data(), n), true);
    n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++n)
        write_gbuffer_pixel(scene, camera, rays[n], hits[n], size_t(y) * g.width + x, g);
  });
  return uint64_t(g.width) * g.height;
}

}  // namespace bounce
