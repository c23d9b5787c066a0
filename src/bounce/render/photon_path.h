// The kernel bodies of photon tracing (seed 000 §5.3.1-5.3.2, multi-bounce), over plain views.
// A path starts at a light (start_photon_path), and at each hit photon_bounce deposits a photon
// (every diffuse hit after the first) and scatters the path or ends it. The k-th photon a path
// deposits comes from its hit at depth k + 1, so a path's photons go to slots first .. first +
// count - 1, with `first` from an exclusive scan of the paths' counts (count-then-scan).
//
// Two launchers share these bodies: the CPU one (photon_tracing.cpp) traces chunks of paths a
// bounce at a time, handing each bounce's rays to the Tracer as one stream, which Embree traces
// faster than single rays; a GPU backend runs trace_photon_path per path, through the trace view,
// once to count and once to write.
#pragma once

#include <cstdint>
#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/octahedral.h"
#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/render/photon_emission.h"
#include "bounce/render/photon_view.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

// Paths ended by Russian roulette still stop here (a closed white room would never end).
inline constexpr int kMaxPhotonDepth = 64;

// What one pass of photon tracing shares between its paths.
struct PhotonPass {
  uint32_t paths = 0;  // paths in the pass (the Hammersley set's size)
  int max_depth = 0;   // the last depth that may scatter
  bool roulette = true;
  vec2 rotation{0.0f};  // Cranley-Patterson shift of the Hammersley set
  uint32_t stream = 0;  // TEA stream
};

// A path between two bounces: the ray it travels along, the flux it carries, its generator.
struct PhotonPath {
  Ray ray;
  vec3 flux{0.0f};
  TeaRng rng;
};

// A photon as stored (photons.h).
struct PhotonDeposit {
  vec3 position;
  vec3 flux;
  uint32_t incident;  // octahedral, direction of travel
  uint32_t normal;    // octahedral, on the side it arrived from
};

BOUNCE_HD inline PhotonPath start_photon_path(const SceneView& scene,
                                              const PhotonEmitterView& emitters,
                                              const PhotonPass& pass, uint32_t i) {
  TeaRng rng = TeaRng::for_path(i, pass.stream);
  const vec2 u = rotate_unit(hammersley(i, pass.paths), pass.rotation);
  const EmittedPhoton e = emit_photon(scene, emitters, u, rng.next2(), pass.paths);
  return {Ray{e.origin, 0.0f, e.direction}, e.flux, rng};
}

// The path met `hit` at `depth` (0: the first hit after leaving the light). Sets *deposit and
// returns 1 in *stored when a photon is deposited there; returns whether the path goes on (its
// ray then holds the next segment).
BOUNCE_HD inline bool photon_bounce(const SceneView& scene, const PhotonPass& pass,
                                    PhotonPath& path, const Hit& hit, int depth,
                                    PhotonDeposit& deposit, bool& stored) {
  stored = false;
  // Nothing, or a sphere light (which absorbs what reaches it).
  if (!hit.valid()) return false;
  const SurfaceHit s = surface_at(scene, hit, path.ray.direction);
  if (depth >= 1) {
    deposit = {s.position, path.flux, oct_pack(path.ray.direction), oct_pack(s.normal)};
    stored = true;
  }
  if (depth >= pass.max_depth) return false;
  // Diffuse bounce, cosine-weighted: the Lambert BRDF times cosine over the pdf is the albedo.
  const vec2 r = path.rng.next2();
  if (pass.roulette) {
    const float survive = glm::min(1.0f, max_component(s.albedo));
    if (!(r.x < survive)) return false;
    path.flux *= s.albedo / survive;
  } else {
    path.flux *= s.albedo;
    if (!(max_component(path.flux) > 0.0f)) return false;
  }
  const vec3 dir =
      Basis::from_normal(s.normal).to_world(sample_cosine_hemisphere(path.rng.next2()));
  if (glm::dot(dir, s.geometric_normal) <= 0.0f) return false;  // shading normal points inside
  path.ray = Ray{offset_origin(s.position, s.geometric_normal), 0.0f, dir};
  return true;
}

BOUNCE_HD inline void store_photon(const PhotonView& out, uint32_t slot, const PhotonDeposit& d) {
  out.position[slot] = d.position;
  out.flux[slot] = d.flux;
  out.incident[slot] = d.incident;
  out.normal[slot] = d.normal;
}

// Path i, whole, through the trace view: the per-path kernel. Calls deposit(k, photon) for its
// k-th photon and returns how many it deposited and, in *rays, the rays it traced.
template <typename Deposit>
BOUNCE_HD uint32_t trace_photon_path(const SceneView& scene, const TraceView& trace,
                                     const PhotonEmitterView& emitters, const PhotonPass& pass,
                                     uint32_t i, Deposit&& deposit, uint32_t& rays) {
  PhotonPath path = start_photon_path(scene, emitters, pass, i);
  uint32_t count = 0;
  rays = 0;
  for (int depth = 0;; ++depth) {
    const Hit hit = trace.intersect(path.ray);
    ++rays;
    PhotonDeposit d;
    bool stored;
    const bool goes_on = photon_bounce(scene, pass, path, hit, depth, d, stored);
    if (stored) deposit(count++, d);
    if (!goes_on) return count;
  }
}

}  // namespace bounce
