// The `lhb` technique's per-pixel bodies (seed 001, section 5): paths from each G-buffer surface
// whose indirect rays are answered by the layered hit buffers, and the discontinuity filter that
// merges the interleaved samples of neighbouring pixels. Host/device functions over plain views.
#pragma once

#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/surface.h"
#include "bounce/techniques/lhb/direction_sets.h"
#include "bounce/techniques/lhb/lhb_query.h"
#include "bounce/techniques/path/path_tracer.h"

namespace bounce {

struct LhbGatherSettings {
  int paths = 1;             // per pixel per frame
  int bounces = 2;           // indirect bounces (light reflected this many times before x)
  float cone_radius = 1.5f;  // disc jitter of the projected origin, in texels (seed 5.5)
  int interleave = 4;        // n: the n x n pixels of a tile draw n^2 rotations of one set
  int interleave_step = 1;   // pixels per interleaving cell: the low-resolution factor, so that
                             // the low-resolution samples cycle through all n^2 sets
  uint32_t frame = 0;        // new samples every frame
  uint32_t seed = 0;
};

// What the gather reads: the scene (materials, lights, shadow rays), the buffers and their
// directions.
struct LhbScene {
  PathScene path;  // scene view, trace view (shadow rays), light picker
  LhbView buffers;
  DirectionSetView directions;
};

// The (mesh, triangle) of a global triangle id: the last mesh whose first id is <= prim.
BOUNCE_HD inline uvec2 lhb_mesh_triangle(const SceneView& scene, uint32_t prim) {
  uint32_t lo = 0, hi = scene.mesh_count;  // answer in [lo, hi)
  while (hi - lo > 1) {
    const uint32_t mid = (lo + hi) / 2;
    if (scene.triangle_offsets[mid] <= prim)
      lo = mid;
    else
      hi = mid;
  }
  return {lo, prim - scene.triangle_offsets[lo]};
}

// A Hit on triangle `prim` at point p (a buffer hit lies on the texel's ray at the texel centre's
// depth, so it is projected onto the triangle's plane and clamped into the triangle).
BOUNCE_HD inline Hit lhb_hit_on(const SceneView& scene, uint32_t prim, vec3 p, float t) {
  const uvec2 mt = lhb_mesh_triangle(scene, prim);
  const MeshView& mesh = scene.meshes[mt.x];
  const uvec3 tri = mesh.triangles[mt.y];
  const vec3 a = mesh.positions[tri.x], e1 = mesh.positions[tri.y] - a,
             e2 = mesh.positions[tri.z] - a, q = p - a;
  // Least-squares barycentrics of q in the plane of (e1, e2).
  const float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const float q1 = glm::dot(q, e1), q2 = glm::dot(q, e2);
  const float det = d11 * d22 - d12 * d12;
  vec2 b(1.0f / 3.0f);
  if (det > 0.0f) b = vec2(d22 * q1 - d12 * q2, d11 * q2 - d12 * q1) / det;
  b = glm::max(b, vec2(0.0f));
  const float s = b.x + b.y;
  if (s > 1.0f) b /= s;
  Hit hit;
  hit.t = t;
  hit.mesh = mt.x;
  hit.triangle = mt.y;
  hit.barycentric = b;
  return hit;
}

// The 2D sample of path `k` at pixel (x, y) for its first indirect direction: interleaved
// sampling after Keller and Heidrich (2001). One Halton sequence (bases 2, 3) serves every pixel;
// pixel (x mod n, y mod n) of each n x n tile shifts it by its own of n^2 offsets, which are
// themselves a stratified 2D set, so a tile's pixels together sample n^2 shifted copies: what
// the discontinuity filter merges back (seed 001 section 5.6 names the scheme only).
BOUNCE_HD inline vec2 lhb_interleaved_sample(int x, int y, int n, uint32_t k) {
  const uint32_t s = uint32_t(x % n) + uint32_t(n) * uint32_t(y % n);
  const uint32_t sets = uint32_t(n * n);
  const vec2 offset((float(s) + 0.5f) / float(sets), radical_inverse(3, s + 1));
  const vec2 h(radical_inverse(2, k + 1), radical_inverse(3, k + 1));
  return glm::fract(h + offset);
}

// Radiance arriving at surface x from above, through the buffers, with 1..bounces bounces,
// cosine-weighted and divided by x's albedo (the filter works on it; the caller multiplies the
// albedo back): each vertex's direct light comes from one light sample with a shadow ray (the
// path tracer's next-event estimation); emitters found by a buffer hit are not counted again.
// u0 is the first direction's 2D sample; later ones come from rng.
BOUNCE_HD inline vec3 lhb_incoming(const LhbScene& ls, const LhbGatherSettings& settings,
                                   const SurfaceHit& start, vec2 u0, uint32_t start_prim,
                                   Pcg32& rng, PathCounters& counters) {
  PathSettings nee;
  nee.strategy = LightStrategy::kLightOnly;
  // One light by power, not resampled: on aggressor (85 lights, 320x180) 8 candidates took
  // indirect light from 4.6-4.9 to 7.1-8.0 ms for 3-11% less MSE8 (docs/benchmarks.md).
  nee.light_candidates = 1;
  vec3 radiance(0.0f), throughput(1.0f);
  SurfaceHit x = start;
  uint32_t x_prim = start_prim;
  vec2 u = u0;
  for (int bounce = 1; bounce <= settings.bounces; ++bounce) {
    if (bounce > 1) {
      throughput *= x.albedo;  // Lambertian with cosine-weighted directions (seed eq. 5.17)
      u = rng.next2();
    }
    const vec2 jitter = settings.cone_radius * sample_concentric_disk(rng.next2());
    if (max_component(throughput) <= 0.0f) break;
    const vec3 wanted = Basis::from_normal(x.normal).to_world(sample_cosine_hemisphere(u));
    const int dir = ls.directions.nearest(glm::normalize(wanted));
    const vec3 d = ls.directions.directions[dir];
    // A snapped direction below the face would start inside the surface: the sample ends.
    if (glm::dot(d, x.geometric_normal) <= 0.0f) break;
    const LhbHit h = lhb_closest(ls.buffers, dir, x.position, 0.0f, jitter, x_prim);
    ++counters.rays;
    if (!h.valid()) break;
    const Hit hit = lhb_hit_on(ls.path.scene, h.prim, h.point, h.t);
    const SurfaceHit y = surface_at(ls.path.scene, hit, d);
    // Light from a surface that faces away from x (seen from behind through a texel's
    // approximation) does not arrive.
    if (glm::dot(y.geometric_normal, d) >= 0.0f) break;
    const vec3 origin = offset_origin(y.position, y.geometric_normal);
    radiance += throughput * sample_one_light(ls.path, nee, y, origin, -d, rng, counters);
    x = y;
    x_prim = h.prim;
  }
  return is_finite(radiance) ? radiance : vec3(0.0f);
}

// Incoming indirect radiance at G-buffer pixel (x, y), averaged over the frame's paths (0 where
// the pixel has no surface).
BOUNCE_HD inline vec3 lhb_pixel(const LhbScene& ls, const LhbGatherSettings& settings,
                                const ConstGBufferView& g, int x, int y, PathCounters& counters) {
  const uint32_t i = uint32_t(g.index(x, y));
  if (!g.hit(i)) return vec3(0.0f);
  const SurfaceHit s = g.surface(i);
  const int n = settings.interleave > 0 ? settings.interleave : 1;
  vec3 sum(0.0f);
  for (int k = 0; k < settings.paths; ++k) {
    const uint32_t sample = settings.frame * uint32_t(settings.paths) + uint32_t(k);
    Pcg32 rng = path_rng(i, sample, settings.seed);
    const int step = settings.interleave_step > 0 ? settings.interleave_step : 1;
    const vec2 u0 = lhb_interleaved_sample(x / step, y / step, n, sample);
    sum += lhb_incoming(ls, settings, s, u0, g.primitive[i], rng, counters);
  }
  return sum / float(settings.paths);
}

// What the discontinuity filter gives with a window of one pixel, for a row of `count` pixels:
// the albedo times the incoming light where there is a surface, 0 elsewhere.
BOUNCE_HD inline void lhb_albedo_times_incoming(const vec3* albedo, const uint32_t* primitive,
                                                const vec3* incoming, vec3* out, int count) {
  // Over the floats, masked by a 0/1 factor (both inputs are finite: the estimates are, and the
  // G-buffer's albedo is): a loop the compiler vectorises.
  const float* a = &albedo[0].x;
  const float* in = &incoming[0].x;
  float* o = &out[0].x;
  for (int i = 0; i < count; ++i) {
    const float hit = float(primitive[i] != kNoPrimitive);
    for (int c = 0; c < 3; ++c) o[3 * i + c] = hit * (a[3 * i + c] * in[3 * i + c]);
  }
}

// The discontinuity buffer (seed 001 section 5.6 names it; Keller 1998, Wald et al. 2002): the
// incoming indirect light of pixel (x, y) averaged over the n x n window around it, taking only
// neighbours on the same surface (normals within normal_dot, positions within `distance` of each
// other relative to the view depth), so the interleaved tile's n^2 sample sets merge while edges
// stay sharp. Returns the average times the pixel's albedo: its reflected indirect radiance.
BOUNCE_HD inline vec3 lhb_discontinuity_pixel(const ConstGBufferView& g, const vec3* incoming,
                                              int x, int y, int n, float normal_dot,
                                              float distance) {
  const uint32_t i = uint32_t(g.index(x, y));
  if (!g.hit(i)) return vec3(0.0f);
  const vec3 ni = g.normal[i], pi = g.position[i];
  const float reach = distance * g.depth[i];
  const int lo = -(n - 1) / 2, hi = n / 2;  // n x n: -1..2 for 4, -1..1 for 3
  vec3 sum(0.0f);
  float count = 0.0f;
  for (int dy = lo; dy <= hi; ++dy)
    for (int dx = lo; dx <= hi; ++dx) {
      const int xx = x + dx, yy = y + dy;
      if (xx < 0 || yy < 0 || xx >= g.width || yy >= g.height) continue;
      const uint32_t j = uint32_t(g.index(xx, yy));
      if (!g.hit(j) || glm::dot(g.normal[j], ni) < normal_dot) continue;
      if (glm::length(g.position[j] - pi) > reach) continue;
      sum += incoming[j];
      count += 1.0f;
    }
  return g.albedo[i] * (sum / glm::max(count, 1.0f));
}

}  // namespace bounce
