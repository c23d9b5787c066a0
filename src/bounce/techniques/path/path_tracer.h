// The path-tracing kernel: radiance along one path, unbiased, with next-event estimation and
// multiple importance sampling. Host/device functions over plain views (the scene view, the trace
// view, the light picker's view), shared by the `path` technique and the offline reference
// renderer. README.md in this folder explains the estimator and its choices.
#pragma once

#include <cstdint>

#include <limits>

#include "bounce/core/color.h"
#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/rng.h"
#include "bounce/render/brdf.h"
#include "bounce/render/bsdf_sampling.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/light_pdf.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/light_resampling.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/trace_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// How light from area and sphere lights is estimated at each vertex. kMis is the estimator; the
// other two exist to check it (each alone is unbiased too, with more variance).
enum class LightStrategy : uint8_t { kMis, kLightOnly, kBsdfOnly };

// Paths never get longer than this many bounces, even with no limit set: only a white furnace
// (albedo 1, where Russian roulette never ends a path) gets there.
inline constexpr int kMaxPathBounces = 1024;

struct PathSettings {
  // Light is counted by its indirect bounces: the surfaces it reflected off between leaving an
  // emitter and reaching the start vertex (which reflects it towards the viewer). Direct light
  // has 0 bounces. Paths count light with min_bounces..max_bounces bounces; max_bounces < 0
  // means no limit. The reference uses min 0; the technique's indirect term uses min 1.
  int min_bounces = 0;
  int max_bounces = -1;
  // Russian roulette decides every continuation from vertex rr_start on (vertex 0 is the start):
  // the path survives with probability min(1, max channel of its throughput).
  int rr_start = 3;
  LightStrategy strategy = LightStrategy::kMis;
  // Next-event estimation in scenes with more lights than resample_above_lights (LightPicker
  // entries) keeps one of light_candidates light samples drawn by power, resampled by their
  // unshadowed contribution (light_resampling.h), as direct light does in such scenes
  // (DirectSettings::max_looped_lights): a light picked by power alone is, in a level with
  // dozens of lamps, mostly one out of the vertex's sight. In scenes with 2 to
  // resample_above_lights lights it keeps one of a sample of every light, the same way: a
  // flashlight among a level's far brighter lamps, picked by power, lit its beam in a path or
  // two out of dozens. With one candidate, and with a single light, one sample drawn by power.
  uint32_t resample_above_lights = kResampleAboveLights;
  int light_candidates = kLightCandidates;
};

// What a path reads: the scene, its ray queries (sphere lights included) and the light pick.
struct PathScene {
  SceneView scene;
  TraceView trace;
  LightPickerView lights;
  // Area light of each triangle by global id (LightPicker::area_light_of_triangle), -1 for
  // non-emitters.
  const int32_t* area_light_of_triangle = nullptr;

  BOUNCE_HD float pick_pmf(uint32_t entry) const {
    return lights.empty() ? 0.0f : lights.pmf[entry];
  }
};

// The views of a scene's data, its tracer and its light picker, valid while they are.
inline PathScene path_scene(const SceneView& scene, const Tracer& tracer,
                            const LightPicker& lights) {
  return {scene, tracer.view(), lights.view(), lights.area_light_of_triangle.data()};
}

struct PathCounters {
  uint64_t rays = 0;       // intersection and shadow rays
  uint64_t nonfinite = 0;  // samples dropped because they were NaN or infinite
};

BOUNCE_HD inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// The generator of one path: a function of the pixel, the sample index and the seed only, so
// images do not depend on how the work is split over threads.
BOUNCE_HD inline Pcg32 path_rng(uint32_t pixel, uint32_t sample, uint32_t seed) {
  return Pcg32(splitmix64((uint64_t(pixel) << 32) | sample), seed);
}

// One light sample's unshadowed estimate at x: a point u places on light `entry`, seen from p
// (x's offset origin); its radiance towards wo over the sample's probability times `pick_pdf`
// (the entry's chance to be the one sampled), with the light strategy's MIS weight for a pick by
// power. `ray` is its shadow ray; the estimate is 0 where the sample brings nothing.
BOUNCE_HD inline vec3 light_entry_estimate(const PathScene& ps, const PathSettings& settings,
                                           const SurfaceHit& x, vec3 p, vec3 wo, uint32_t entry,
                                           float pick_pdf, vec2 u, Ray& ray) {
  const float power_pdf = ps.lights.pmf[entry];
  if (!(power_pdf > 0.0f)) return vec3(0.0f);
  const EntrySample sample = sample_light_entry(ps.scene, ps.lights.light_count, entry, p, u);
  const LightSample& ls = sample.ls;
  const bool delta = sample.delta;
  if (!ls.valid()) return vec3(0.0f);
  // BSDF sampling cannot find a point light; it finds area and sphere lights on its own.
  if (!delta && settings.strategy == LightStrategy::kBsdfOnly) return vec3(0.0f);
  const float cos_i = glm::dot(x.normal, ls.wi);
  // Light from below the face itself cannot arrive, whatever the shading normal says.
  if (cos_i <= 0.0f || glm::dot(x.geometric_normal, ls.wi) <= 0.0f) return vec3(0.0f);
  const vec3 f = eval_brdf(x, wo, ls.wi);
  if (max_component(f) <= 0.0f) return vec3(0.0f);
  float weight = 1.0f;
  if (!delta && settings.strategy == LightStrategy::kMis)
    weight = power_heuristic(power_pdf * ls.pdf, bsdf_pdf(x, wo, ls.wi));
  if (weight <= 0.0f) return vec3(0.0f);
  ray = shadow_ray(p, ls);
  return f * ls.weight * (cos_i * weight / pick_pdf);
}

// light_entry_estimate for the light entry u_pick picks by power.
BOUNCE_HD inline vec3 light_sample_estimate(const PathScene& ps, const PathSettings& settings,
                                            const SurfaceHit& x, vec3 p, vec3 wo, float u_pick,
                                            vec2 u, Ray& ray) {
  const uint32_t entry = ps.lights.pick(u_pick);
  return light_entry_estimate(ps, settings, x, p, wo, entry, ps.lights.pmf[entry], u, ray);
}

// Next-event estimation at x: one light sample, one shadow ray from p (x's offset origin). The
// sample is drawn by power, or resampled by unshadowed contribution from a sample of every light
// (scenes with few lights) or from candidates drawn by power (scenes with many lights;
// PathSettings::light_candidates). The MIS weights stay those of the sample drawn by power, on
// both sides (emission_weight): they sum to one whatever the light sample's actual density, and
// resampling an estimate that carries its weight leaves it unbiased. Returns the radiance x
// reflects towards wo from that sample.
BOUNCE_HD inline vec3 sample_one_light(const PathScene& ps, const PathSettings& settings,
                                       const SurfaceHit& x, vec3 p, vec3 wo, Pcg32& rng,
                                       PathCounters& counters) {
  const bool resample = settings.light_candidates > 1 && ps.lights.count > 1;
  const bool every_light = resample && ps.lights.count <= settings.resample_above_lights;
  const int m = !resample ? 1 : every_light ? int(ps.lights.count) : settings.light_candidates;
  // Each candidate draws its numbers first, so that the path's later decisions use the same
  // ones whatever happens here.
  Ray ray;
  vec3 estimate(0.0f);
  if (m == 1) {
    const float u_pick = rng.next_float();
    const vec2 u = rng.next2();
    if (ps.lights.empty()) return vec3(0.0f);
    estimate = light_sample_estimate(ps, settings, x, p, wo, u_pick, u, ray);
  } else {
    // A candidate's estimate is an unbiased estimate of its light's share (every light) or of
    // all the light (a pick by power); the kept one is scaled by (sum of weights) / (its own),
    // and over m picks by power by 1 / m as well.
    LightReservoir reservoir;
    for (int j = 0; j < m; ++j) {
      const float u_pick = rng.next_float();
      const vec2 u = rng.next2();
      const float u_keep = rng.next_float();
      Ray candidate_ray;
      const vec3 e =
          every_light
              ? light_entry_estimate(ps, settings, x, p, wo, uint32_t(j), 1.0f, u, candidate_ray)
              : light_sample_estimate(ps, settings, x, p, wo, u_pick, u, candidate_ray);
      const float w = luminance(e);
      if (!(w > 0.0f)) continue;
      if (reservoir.offer(w, u_keep)) {
        estimate = e;
        ray = candidate_ray;
      }
    }
    if (reservoir.empty()) return vec3(0.0f);
    estimate *= reservoir.total / ((every_light ? 1.0f : float(m)) * reservoir.kept);
  }
  if (max_component(estimate) <= 0.0f) return vec3(0.0f);
  ++counters.rays;
  // Sphere lights are trace geometry: the one occlusion query sees them too.
  if (ps.trace.occluded(ray)) return vec3(0.0f);
  return estimate;
}

// MIS weight of emission found by a BSDF-sampled direction whose pdf was bsdf_pdf, when the
// light strategy would have found it with pdf light_pdf.
BOUNCE_HD inline float emission_weight(const PathSettings& settings, float bsdf_pdf,
                                       float light_pdf) {
  switch (settings.strategy) {
    case LightStrategy::kMis:
      return power_heuristic(bsdf_pdf, light_pdf);
    case LightStrategy::kLightOnly:
      return light_pdf > 0.0f ? 0.0f : 1.0f;  // what light sampling cannot find stays here
    case LightStrategy::kBsdfOnly:
      return 1.0f;
  }
  return 1.0f;
}

// Radiance that `start` reflects towards wo (its own emission excluded), from light with
// settings.min_bounces..max_bounces bounces.
BOUNCE_HD inline vec3 reflected_radiance(const PathScene& ps, const PathSettings& settings,
                                         const SurfaceHit& start, vec3 wo, Pcg32& rng,
                                         PathCounters& counters) {
  const int last =
      settings.max_bounces < 0 ? kMaxPathBounces : glm::min(settings.max_bounces, kMaxPathBounces);
  vec3 radiance(0.0f), throughput(1.0f);
  SurfaceHit x = start;
  // At vertex `bounce`, light sampled there or found by its BSDF ray has `bounce` bounces.
  for (int bounce = 0; bounce <= last; ++bounce) {
    const bool counts = bounce >= settings.min_bounces;
    const vec3 p = offset_origin(x.position, x.geometric_normal);
    if (counts) radiance += throughput * sample_one_light(ps, settings, x, p, wo, rng, counters);

    const float u_lobe = rng.next_float();
    const vec2 u = rng.next2();
    const BsdfSample b = sample_bsdf(x, wo, u_lobe, u);
    if (!b.valid() || glm::dot(x.geometric_normal, b.wi) <= 0.0f) break;
    throughput *= b.f * (glm::dot(x.normal, b.wi) / b.pdf);
    if (bounce >= settings.rr_start) {
      const float survive = glm::min(1.0f, max_component(throughput));
      if (!(rng.next_float() < survive)) break;
      throughput /= survive;
    }

    const Hit hit = ps.trace.intersect(Ray{p, 0.0f, b.wi, std::numeric_limits<float>::infinity()});
    ++counters.rays;
    if (hit.sphere_light()) {
      // Sphere lights emit and reflect nothing: the path ends on them.
      if (counts) {
        const LightRecord& light = ps.scene.lights[hit.light];
        const float light_pdf = ps.pick_pmf(hit.light) * sphere_light_pdf(light, p);
        radiance += throughput * light.radiance * emission_weight(settings, b.pdf, light_pdf);
      }
      break;
    }
    if (!hit.valid()) {
      // The path leaves the scene: the environment's radiance, weighted against its sampling.
      if (counts && ps.scene.environment >= 0) {
        const float light_pdf =
            ps.pick_pmf(uint32_t(ps.scene.environment)) * environment_light_pdf(ps.scene, b.wi);
        radiance +=
            throughput * ps.scene.background(b.wi) * emission_weight(settings, b.pdf, light_pdf);
      }
      break;
    }
    const SurfaceHit s = surface_at(ps.scene, hit, b.wi);
    if (counts && max_component(s.emission) > 0.0f) {
      const int32_t area = ps.area_light_of_triangle[ps.scene.triangle_id(hit.mesh, hit.triangle)];
      float light_pdf = 0.0f;
      if (area >= 0)
        light_pdf =
            ps.pick_pmf(ps.lights.light_count + uint32_t(area)) *
            area_light_pdf(ps.scene.area_lights[area], hit.t, glm::dot(s.geometric_normal, -b.wi));
      radiance += throughput * s.emission * emission_weight(settings, b.pdf, light_pdf);
    }
    x = s;
    wo = -b.wi;
  }
  if (!is_finite(radiance)) {
    ++counters.nonfinite;
    return vec3(0.0f);
  }
  return radiance;
}

// Radiance arriving at `origin` from unit direction -direction: what a camera ray sees, emitters
// included (their emission at weight one: no light sample is taken at a camera).
BOUNCE_HD inline vec3 ray_radiance(const PathScene& ps, const PathSettings& settings, vec3 origin,
                                   vec3 direction, Pcg32& rng, PathCounters& counters) {
  const Hit hit =
      ps.trace.intersect(Ray{origin, 0.0f, direction, std::numeric_limits<float>::infinity()});
  ++counters.rays;
  if (hit.sphere_light()) return ps.scene.lights[hit.light].radiance;
  if (!hit.valid()) return ps.scene.background(direction);
  const SurfaceHit s = surface_at(ps.scene, hit, direction);
  return s.emission + reflected_radiance(ps, settings, s, -direction, rng, counters);
}

// The `path` technique's per-pixel body: the sum of `samples` paths' reflected radiance from
// G-buffer pixel i towards `eye` (0 where the pixel has no surface), path k drawing the numbers of
// sample first_sample + k.
BOUNCE_HD inline vec3 path_pixel(const PathScene& ps, const PathSettings& settings,
                                 const ConstGBufferView& g, uint32_t i, vec3 eye,
                                 uint32_t first_sample, int samples, uint32_t seed,
                                 PathCounters& counters) {
  vec3 sum(0.0f);
  if (!g.hit(i)) return sum;
  const SurfaceHit x = g.surface(i);
  const vec3 wo = glm::normalize(eye - x.position);
  for (int k = 0; k < samples; ++k) {
    Pcg32 rng = path_rng(i, first_sample + uint32_t(k), seed);
    sum += reflected_radiance(ps, settings, x, wo, rng, counters);
  }
  return sum;
}

}  // namespace bounce
