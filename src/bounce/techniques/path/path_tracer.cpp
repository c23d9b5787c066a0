#include "bounce/techniques/path/path_tracer.h"

#include <limits>

#include "bounce/render/bsdf_sampling.h"
#include "bounce/render/light_pdf.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/surface.h"

namespace bounce {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

PathVertex vertex_of(const SurfaceHit& s) {
  return {s.position, s.geometric_normal, {s.normal, s.albedo, s.roughness, s.f0}};
}

// Whether anything blocks the segment: scene geometry, or a sphere light (which the Tracer does
// not hold, but which stops BSDF rays, so light samples must see it too).
bool blocked(const PathScene& ps, const Ray& ray, PathCounters& counters) {
  ++counters.rays;
  if (ps.tracer.occluded(ray)) return true;
  return ps.lights.has_sphere_lights &&
         intersect_sphere_lights(ps.scene, ray.origin, ray.direction, ray.tmax).light >= 0;
}

// Next-event estimation at x: one light picked by power, one sample of it, one shadow ray from
// p (x's offset origin). Returns the radiance x reflects towards wo from that sample.
vec3 sample_one_light(const PathScene& ps, const PathSettings& settings, const PathVertex& x,
                      vec3 p, vec3 wo, Pcg32& rng, PathCounters& counters) {
  // Draw the numbers first, so that the path's later decisions use the same ones whatever
  // happens here.
  const float u_pick = rng.next_float();
  const vec2 u = rng.next2();
  if (ps.lights.empty()) return vec3(0.0f);
  const uint32_t entry = ps.lights.pick(u_pick);
  const float pick_pdf = ps.lights.pmf[entry];
  if (!(pick_pdf > 0.0f)) return vec3(0.0f);

  LightSample ls;
  bool delta = false;
  if (entry < ps.lights.light_count) {
    const Light& light = ps.scene.lights[entry];
    if (light.type == LightType::kSphere) {
      ls = sample_sphere_light(light, p, u);
    } else {
      ls = sample_punctual_light(light, p);
      delta = true;
    }
  } else {
    ls = sample_area_light(ps.scene, ps.scene.area_lights[entry - ps.lights.light_count], p, u);
  }
  if (!ls.valid()) return vec3(0.0f);
  // BSDF sampling cannot find a point light; it finds area and sphere lights on its own.
  if (!delta && settings.strategy == LightStrategy::kBsdfOnly) return vec3(0.0f);
  const float cos_i = glm::dot(x.surface.normal, ls.wi);
  // Light from below the face itself cannot arrive, whatever the shading normal says.
  if (cos_i <= 0.0f || glm::dot(x.geometric_normal, ls.wi) <= 0.0f) return vec3(0.0f);
  const vec3 f = eval_brdf(x.surface, wo, ls.wi);
  if (max_component(f) <= 0.0f) return vec3(0.0f);
  float weight = 1.0f;
  if (!delta && settings.strategy == LightStrategy::kMis)
    weight = power_heuristic(pick_pdf * ls.pdf, bsdf_pdf(x.surface, wo, ls.wi));
  if (weight <= 0.0f) return vec3(0.0f);
  // Stop just short of the sampled point so the light's own surface does not block it.
  const Ray shadow{p, 0.0f, ls.wi, ls.distance * (1.0f - 1e-4f)};
  if (blocked(ps, shadow, counters)) return vec3(0.0f);
  return f * ls.weight * (cos_i * weight / pick_pdf);
}

// MIS weight of emission found by a BSDF-sampled direction whose pdf was bsdf_pdf, when the
// light strategy would have found it with pdf light_pdf.
float emission_weight(const PathSettings& settings, float bsdf_pdf, float light_pdf) {
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

}  // namespace

Pcg32 path_rng(uint32_t pixel, uint32_t sample, uint32_t seed) {
  return Pcg32(splitmix64((uint64_t(pixel) << 32) | sample), seed);
}

vec3 reflected_radiance(const PathScene& ps, const PathSettings& settings, const PathVertex& start,
                        vec3 wo, Pcg32& rng, PathCounters& counters) {
  const int last =
      settings.max_bounces < 0 ? kMaxPathBounces : glm::min(settings.max_bounces, kMaxPathBounces);
  vec3 radiance(0.0f), throughput(1.0f);
  PathVertex x = start;
  // At vertex `bounce`, light sampled there or found by its BSDF ray has `bounce` bounces.
  for (int bounce = 0; bounce <= last; ++bounce) {
    const bool counts = bounce >= settings.min_bounces;
    const vec3 p = offset_origin(x.position, x.geometric_normal);
    if (counts) radiance += throughput * sample_one_light(ps, settings, x, p, wo, rng, counters);

    const float u_lobe = rng.next_float();
    const vec2 u = rng.next2();
    const BsdfSample b = sample_bsdf(x.surface, wo, u_lobe, u);
    if (!b.valid() || glm::dot(x.geometric_normal, b.wi) <= 0.0f) break;
    throughput *= b.f * (glm::dot(x.surface.normal, b.wi) / b.pdf);
    if (bounce >= settings.rr_start) {
      const float survive = glm::min(1.0f, max_component(throughput));
      if (!(rng.next_float() < survive)) break;
      throughput /= survive;
    }

    const Hit hit = ps.tracer.intersect(Ray{p, 0.0f, b.wi, kInfinity});
    ++counters.rays;
    if (ps.lights.has_sphere_lights) {
      const SphereLightHit sphere =
          intersect_sphere_lights(ps.scene, p, b.wi, hit.valid() ? hit.t : kInfinity);
      if (sphere.light >= 0) {
        // Sphere lights emit and reflect nothing: the path ends on them.
        if (counts) {
          const Light& light = ps.scene.lights[sphere.light];
          const float light_pdf =
              ps.lights.light_pmf(uint32_t(sphere.light)) * sphere_light_pdf(light, p);
          radiance += throughput * light.radiance * emission_weight(settings, b.pdf, light_pdf);
        }
        break;
      }
    }
    if (!hit.valid()) break;
    const SurfaceHit s = surface_at(ps.scene, hit, b.wi);
    if (counts && max_component(s.emission) > 0.0f) {
      const uint32_t triangle = ps.scene.triangle_offsets[hit.mesh] + hit.triangle;
      const int32_t area = ps.lights.area_light_of_triangle[triangle];
      float light_pdf = 0.0f;
      if (area >= 0)
        light_pdf =
            ps.lights.area_light_pmf(uint32_t(area)) *
            area_light_pdf(ps.scene.area_lights[area], hit.t, glm::dot(s.geometric_normal, -b.wi));
      radiance += throughput * s.emission * emission_weight(settings, b.pdf, light_pdf);
    }
    x = vertex_of(s);
    wo = -b.wi;
  }
  if (!is_finite(radiance)) {
    ++counters.nonfinite;
    return vec3(0.0f);
  }
  return radiance;
}

vec3 ray_radiance(const PathScene& ps, const PathSettings& settings, vec3 origin, vec3 direction,
                  Pcg32& rng, PathCounters& counters) {
  const Hit hit = ps.tracer.intersect(Ray{origin, 0.0f, direction, kInfinity});
  ++counters.rays;
  if (ps.lights.has_sphere_lights) {
    const SphereLightHit sphere =
        intersect_sphere_lights(ps.scene, origin, direction, hit.valid() ? hit.t : kInfinity);
    if (sphere.light >= 0) return ps.scene.lights[sphere.light].radiance;
  }
  if (!hit.valid()) return vec3(0.0f);
  const SurfaceHit s = surface_at(ps.scene, hit, direction);
  return s.emission + reflected_radiance(ps, settings, vertex_of(s), -direction, rng, counters);
}

}  // namespace bounce
