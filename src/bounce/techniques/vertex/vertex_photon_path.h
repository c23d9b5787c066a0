// The vertex technique's photon paths (seed 004 §3.1.1, Fig 5.3; notes/seed-004.md §2.2-2.6):
// a photon leaves a light along a precomputed point-set direction, is stored where it lands (when
// direct light is stored), and splits into `splits` photons of 1/splits the power along
// precomputed bounce directions rotated into the hit's frame, down to `recursion_depth` levels.
// Beyond the seed, each photon of the last level may go on as a single path ended by Russian
// roulette, so light of every bounce count arrives. Kernel bodies over plain views.
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/photon_emission.h"
#include "bounce/render/photon_path.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray_triangle.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

// The deepest split level (splits^depth photons per path: 36^4 is already 1.7 million).
inline constexpr int kMaxRecursionDepth = 4;
// Precomputed bounce direction sets a split picks from (by a hash of the path and the split).
inline constexpr uint32_t kBounceSets = 64;
// Photons reflect with each texture's mean colour, as the seed's do with a texture's average
// (its vertex albedo), not with the texel where they land: a photon lands anywhere in the level,
// its four texels were cache misses (a third of a level's photon trace, 2.7 ms at 10,000
// photons). The pixels' shading still reads every texel.
inline constexpr bool kPhotonMeanTextures = true;

// Where one photon path starts: which emitter (LightPicker entry) and its local direction(s)
// from the emitter's point set; `u` places the point on area and sphere lights.
struct VertexPathStart {
  uint32_t emitter = 0;
  vec3 local_direction{0.0f, 0.0f, 1.0f};  // in the emitter's frame (see emit_vertex_photon)
  vec2 u{0.5f};
  float azimuth = 0.0f;  // turns the local direction about its axis (fresh sets at rest)
  vec3 flux{0.0f};       // W: the emitter's power over its paths in a frame
};

// A path's first ray. Point lights: the direction is a sphere point; spot lights: a point of the
// cone's cap around the light's axis (flux weighted by the falloff over its mean); directional
// lights: the disc point u across the scene; sphere and area lights: a point u on the light and a
// cosine-weighted hemisphere direction about its normal.
BOUNCE_HD inline EmittedPhoton emit_vertex_photon(const SceneView& scene,
                                                  const PhotonEmitterView& emitters,
                                                  const VertexPathStart& start) {
  const uint32_t light_count = emitters.picker.light_count;
  const float ca = glm::cos(start.azimuth), sa = glm::sin(start.azimuth);
  const vec3 turned(ca * start.local_direction.x - sa * start.local_direction.y,
                    sa * start.local_direction.x + ca * start.local_direction.y,
                    start.local_direction.z);
  if (start.emitter >= light_count)
    return photon_from_area_light(scene, scene.area_lights[start.emitter - light_count], start.u,
                                  turned, start.flux);
  return photon_from_light(scene.lights[start.emitter], emitters, start.u, turned, start.flux);
}

// The closest triangle by testing every one (Moller-Trumbore), and the sphere lights: what the
// seed's BSP_tree = false compares against.
BOUNCE_HD inline Hit intersect_every_triangle(const SceneView& scene, const TraceView& trace,
                                              const Ray& ray) {
  Hit hit;
  float best = ray.tmax;
  for (uint32_t m = 0; m < scene.mesh_count; ++m) {
    const MeshView& mesh = scene.meshes[m];
    for (uint32_t t = 0; t < mesh.triangle_count; ++t) {
      const uvec3 i = mesh.triangles[t];
      Ray nearer = ray;
      nearer.tmax = best;
      float d = 0.0f;
      vec2 b(0.0f);
      if (intersect_triangle(mesh.positions[i.x], mesh.positions[i.y], mesh.positions[i.z], nearer,
                             d, b)) {
        best = d;
        hit = Hit{};
        hit.t = d;
        hit.mesh = m;
        hit.triangle = t;
        hit.barycentric = b;
      }
    }
  }
  closest_sphere(trace.spheres, trace.sphere_count, ray, hit);
  return hit;
}

// What the paths of one frame share.
struct VertexTraceView {
  SceneView scene;
  TraceView trace;
  const vec3* bounce_directions = nullptr;  // kBounceSets sets of `splits` directions about +z
  uint32_t splits = 36;                     // diffuse_reflections
  int recursion_depth = 1;                  // split levels
  bool roulette = true;                     // single paths with Russian roulette after them
  bool store_direct = false;                // store the first hits
  int snowball = 1;                         // photons stored per hit
  float snowball_radius = 0.0f;
  uint32_t stream = 0;          // decorrelates the bounce sets and the roulette between seeds
  bool every_triangle = false;  // BSP_tree off: no acceleration structure

  BOUNCE_HD Hit intersect(const Ray& ray) const {
    return every_triangle ? intersect_every_triangle(scene, trace, ray) : trace.intersect(ray);
  }
};
static_assert(std::is_trivially_copyable_v<VertexTraceView>);

// Stores a photon that arrived at s carrying `flux`: `snowball` copies at points of a small disc
// in the hit's tangent plane (the seed's Point_generator; golden-angle points), or the hit itself.
template <typename Deposit>
BOUNCE_HD inline void deposit_photon(const VertexTraceView& v, const SurfaceHit& s, vec3 flux,
                                     Deposit& deposit) {
  if (v.snowball <= 1) {
    deposit(s.position, flux, s.normal);
    return;
  }
  const Basis basis = Basis::from_normal(s.normal);
  const vec3 share = flux / float(v.snowball);
  for (int j = 0; j < v.snowball; ++j) {
    const float r = v.snowball_radius * glm::sqrt((float(j) + 0.5f) / float(v.snowball));
    const float phi = 2.39996323f * float(j);
    deposit(s.position + basis.t * (r * glm::cos(phi)) + basis.b * (r * glm::sin(phi)), share,
            s.normal);
  }
}

// The roulette tail from surface s, which the path reached with `flux` along `incoming`: cosine
// bounces ended by Russian roulette, storing every hit.
template <typename Deposit>
BOUNCE_HD inline uint32_t roulette_tail(const VertexTraceView& v, SurfaceHit s, vec3 flux,
                                        uint32_t key, Deposit& deposit) {
  TeaRng rng = TeaRng::for_path(key, v.stream ^ 0x2545f491u);
  uint32_t rays = 0;
  for (int depth = 0; depth < kMaxPhotonDepth; ++depth) {
    const vec2 r = rng.next2();
    const float survive = glm::min(1.0f, max_component(s.albedo));
    if (!(r.x < survive)) break;
    flux *= s.albedo / survive;
    const vec3 dir = Basis::from_normal(s.normal).to_world(sample_cosine_hemisphere(rng.next2()));
    if (glm::dot(dir, s.geometric_normal) <= 0.0f) break;
    const Ray ray{offset_origin(s.position, s.geometric_normal), 0.0f, dir};
    const Hit hit = v.intersect(ray);
    ++rays;
    if (!hit.valid()) break;
    s = surface_at<kPhotonMeanTextures>(v.scene, hit, dir);
    deposit_photon(v, s, flux, deposit);
  }
  return rays;
}

// Photon path `path` (a global id: the frame's paths are numbered alike every frame) from its
// emitted photon. Calls deposit(position, flux, normal) for every photon it stores, in a fixed
// order; returns the rays it traced.
template <typename Deposit>
BOUNCE_HD inline uint32_t trace_vertex_path(const VertexTraceView& v, const EmittedPhoton& e,
                                            uint32_t path, Deposit& deposit) {
  const Hit first = v.intersect(Ray{e.origin, 0.0f, e.direction});
  uint32_t rays = 1;
  if (!first.valid()) return rays;
  const SurfaceHit s0 = surface_at<kPhotonMeanTextures>(v.scene, first, e.direction);
  if (v.store_direct) deposit_photon(v, s0, e.flux, deposit);

  // Depth-first over the split tree; a frame is a surface whose photon is being split.
  struct Split {
    SurfaceHit s;
    vec3 child_flux;
    uint32_t set;  // which precomputed direction set
    uint32_t key;  // this split's place in the path's tree
    uint32_t next;
  };
  Split stack[kMaxRecursionDepth];
  int top = 0;
  const auto open = [&](const SurfaceHit& s, vec3 flux, uint32_t key) {
    const vec3 child = flux * s.albedo / float(v.splits);
    if (!(max_component(child) > 0.0f)) return;
    stack[top++] = {s, child, hash_u32(key ^ v.stream) % kBounceSets, key, 0};
  };
  const uint32_t root_key = hash_u32(path * 0x9E3779B9u + 0x7f4a7c15u);
  if (v.recursion_depth > 0)
    open(s0, e.flux, root_key);
  else if (v.roulette)
    rays += roulette_tail(v, s0, e.flux, root_key, deposit);

  while (top > 0) {
    Split& f = stack[top - 1];
    if (f.next == v.splits) {
      --top;
      continue;
    }
    const uint32_t j = f.next++;
    const vec3 dir =
        Basis::from_normal(f.s.normal).to_world(v.bounce_directions[size_t(f.set) * v.splits + j]);
    if (glm::dot(dir, f.s.geometric_normal) <= 0.0f) continue;  // shading normal points inside
    const Hit hit = v.intersect(Ray{offset_origin(f.s.position, f.s.geometric_normal), 0.0f, dir});
    ++rays;
    if (!hit.valid()) continue;
    const SurfaceHit s = surface_at<kPhotonMeanTextures>(v.scene, hit, dir);
    const vec3 flux = f.child_flux;
    const uint32_t key = hash_u32(f.key * 31u + j + 1u);
    deposit_photon(v, s, flux, deposit);
    if (top < v.recursion_depth)
      open(s, flux, key);  // f may move: nothing of it is used after this
    else if (v.roulette)
      rays += roulette_tail(v, s, flux, key, deposit);
  }
  return rays;
}

}  // namespace bounce
