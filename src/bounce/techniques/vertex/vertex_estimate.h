// The irradiance estimate at a point of a surface (seed 004 §3.1.4, §3.5; notes/seed-004.md
// §2.9, §2.12): the k nearest photons that pass the sphere slice (and the side test), their flux
// over the disc they cover. Kernel bodies over the kd-tree's view.
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene_view.h"
#include "bounce/techniques/vertex/photon_kdtree.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

struct EstimateSettings {
  int k = 50;                  // max_search_count
  float max_radius = 0.1f;     // the search radius before k photons are found
  bool sphere_slice = true;    // keep photons within slice_half of the tangent plane only
  float slice_half = 0.005f;   // half-thickness of the slice
  bool direction_test = true;  // keep photons that arrived on this side of the surface only
  bool exact = false;          // brute force over every photon (the Exact_photon_map)
  float flux_scale = 1.0f;     // 1 / (ring frames filled): the map holds that many frames
  int final_gather_rays = 0;   // > 0: final gathering with this many rays
  uint32_t final_gather_seed = 0;

  bool operator==(const EstimateSettings&) const = default;
};
static_assert(std::is_trivially_copyable_v<EstimateSettings>);

// Whether photon i may enter the estimate at x with unit normal n (the side the light is wanted
// on): within the slice around the tangent plane, and arrived on n's side.
struct EstimateFilter {
  vec3 x, n;
  bool sphere_slice, direction_test;
  float slice_half;

  // Photon i of tree t (either of the map's).
  BOUNCE_HD bool operator()(const PhotonKdTreeView& t, uint32_t i) const {
    if (sphere_slice && glm::abs(glm::dot(t.position[i] - x, n)) > slice_half) return false;
    if (direction_test && glm::dot(t.normal[i], n) <= 0.0f) return false;
    return true;
  }
  // Whether box [lo, hi] reaches the slice (the search skips a node's photons when it does not:
  // off the tangent plane they would all be rejected, one by one). Generous by 1e-5 of the
  // coordinates' size, so that rounding never skips a photon the test above keeps.
  BOUNCE_HD bool may_accept_box(vec3 lo, vec3 hi) const {
    if (!sphere_slice) return true;
    const vec3 c = 0.5f * (lo + hi), a = glm::abs(n);
    const float d = glm::dot(c - x, n);
    const float r = glm::dot(0.5f * (hi - lo), a);
    const float size = glm::dot(glm::abs(c) + glm::abs(x), a) + r;
    return glm::abs(d) <= slice_half + r + 1e-5f * size;
  }
};

// The k nearest accepted photons at x (heap.capacity is set from the settings).
BOUNCE_HD inline void find_photons(const PhotonMapView& tree, vec3 x, vec3 n,
                                   const EstimateSettings& s, KnnHeap& heap) {
  const EstimateFilter filter{x, n, s.sphere_slice, s.direction_test, s.slice_half};
  heap.capacity = s.k < kMaxSearchCount ? s.k : kMaxSearchCount;
  knn_search(tree, x, s.max_radius, s.exact, filter, heap);
}

// Irradiance (W/m^2) from the photons in the heap. With all k found, the disc reaches the
// farthest one; that photon lies on its rim, so the k - 1 inside it are counted: for photons of
// equal flux spread uniformly, E[(k - 1) / (pi r_k^2)] is exactly their density (r_k^2 is Gamma
// distributed), where the seed's k / (pi r_k^2) is k / (k - 1) too bright. With fewer than k
// found, every photon in the disc of the maximum radius counts.
BOUNCE_HD inline vec3 irradiance_from(const PhotonMapView& tree, const KnnHeap& heap,
                                      const EstimateSettings& s) {
  vec3 sum(0.0f);
  for (int j = 0; j < heap.size; ++j) sum += tree.flux(heap.index[j]);
  float r2 = s.max_radius * s.max_radius;
  if (heap.full() && heap.size > 1) {
    r2 = heap.top();
    sum -= tree.flux(heap.index[0]);  // the heap's top is the farthest
  } else if (heap.full()) {
    r2 = heap.top();  // k = 1: the seed's estimate
  }
  if (!(r2 > 0.0f)) return vec3(0.0f);
  return sum * (s.flux_scale / (kPi * r2));
}

BOUNCE_HD inline vec3 photon_irradiance(const PhotonMapView& tree, vec3 x, vec3 n,
                                        const EstimateSettings& s, KnnHeap& heap) {
  find_photons(tree, x, n, s, heap);
  return irradiance_from(tree, heap, s);
}

// Final gathering (seed §3.2.2): irradiance at x from cosine-distributed rays (stratified, Eq
// 3.10), each ending on a surface whose reflected radiance the photon map estimates there. The map
// must then hold the photons' first hits too (the light the gathered surfaces reflect).
BOUNCE_HD inline vec3 final_gather_irradiance(const SceneView& scene, const TraceView& trace,
                                              const PhotonMapView& tree, vec3 x, vec3 n,
                                              const EstimateSettings& s, uint32_t point,
                                              KnnHeap& heap) {
  const int rays = s.final_gather_rays;
  int side = 1;
  while ((side + 1) * (side + 1) <= rays) ++side;
  const Basis basis = Basis::from_normal(n);
  TeaRng rng = TeaRng::for_path(point, s.final_gather_seed);
  vec3 sum(0.0f);
  for (int j = 0; j < rays; ++j) {
    // side x side strata, then the remainder unstratified.
    vec2 u = rng.next2();
    if (j < side * side) u = (vec2(float(j % side), float(j / side)) + u) / float(side);
    const vec3 dir = basis.to_world(sample_cosine_hemisphere(u));
    const Ray ray{offset_origin(x, n), 0.0f, dir};
    const Hit hit = trace.intersect(ray);
    if (!hit.valid()) continue;
    const SurfaceHit h = surface_at(scene, hit, dir);
    // Radiance leaving the hit towards x is albedo / pi * E there; the cosine-weighted pdf makes
    // E(x) = pi * mean(L) = mean(albedo * E_hit).
    sum += h.albedo * photon_irradiance(tree, h.position, h.normal, s, heap);
  }
  return rays > 0 ? sum / float(rays) : vec3(0.0f);
}

}  // namespace bounce
