#include "bounce/render/photon_emission.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/sampling.h"
#include "bounce/render/light_sampling.h"

namespace bounce {

PhotonEmitters PhotonEmitters::from(const Scene& scene) {
  PhotonEmitters e;
  e.picker = LightPicker::build(scene);
  e.scene_centre = scene.bounds.centre();
  e.scene_radius = std::max(0.5f * scene.bounds.diagonal(), 1e-3f);
  for (const Light& l : scene.lights) e.total_power += l.power(e.scene_radius);
  for (const AreaLight& a : scene.area_lights) e.total_power += a.power();
  return e;
}

EmittedPhoton emit_photon(const Scene& scene, const PhotonEmitters& emitters, vec2 u, vec2 v,
                          uint32_t path_count) {
  // Choose the light with u.x, then stretch u.x back over [0, 1) within its interval.
  const LightPicker& picker = emitters.picker;
  const uint32_t k = picker.pick(u.x);
  const float probability = picker.pmf[k];
  u.x = picker.remap(k, u.x);
  EmittedPhoton p;
  if (k >= picker.light_count) {
    const AreaLight& area = scene.area_lights[k - picker.light_count];
    p.flux = area.power() / (probability * float(path_count));
    const AreaLightPoint q = sample_area_light_point(scene, area, u);
    p.direction = Basis::from_normal(q.normal).to_world(sample_cosine_hemisphere(v));
    p.origin = offset_origin(q.position, q.normal);
    return p;
  }
  const Light& light = scene.lights[k];
  const vec3 power = light.power(emitters.scene_radius);
  p.flux = power / (probability * float(path_count));

  switch (light.type) {
    case LightType::kPoint:
      p.origin = light.position;
      p.direction = sample_uniform_sphere(u);
      break;
    case LightType::kSpot: {
      // Uniform in the outer cone; the falloff weights the flux (its mean over the cone is
      // power / (intensity * cone solid angle), so the expected flux stays right).
      p.origin = light.position;
      p.direction =
          Basis::from_normal(light.direction).to_world(sample_uniform_cone(u, light.cos_outer));
      const float cone = kTwoPi * (1.0f - light.cos_outer);
      const float mean_falloff =
          glm::max(power.x + power.y + power.z, 1e-30f) /
          glm::max((light.intensity.x + light.intensity.y + light.intensity.z) * cone, 1e-30f);
      p.flux *= spot_falloff(light, p.direction) / mean_falloff;
      break;
    }
    case LightType::kDirectional: {
      // A disk across the scene, perpendicular to the light, behind the scene.
      const Basis basis = Basis::from_normal(light.direction);
      const vec2 d = sample_concentric_disk(u) * emitters.scene_radius;
      p.origin = emitters.scene_centre + basis.t * d.x + basis.b * d.y -
                 light.direction * (2.0f * emitters.scene_radius);
      p.direction = light.direction;
      break;
    }
    case LightType::kSphere: {
      const vec3 n = sample_uniform_sphere(u);
      p.origin = light.position + n * light.radius;
      p.origin = offset_origin(p.origin, n);
      p.direction = Basis::from_normal(n).to_world(sample_cosine_hemisphere(v));
      break;
    }
  }
  return p;
}

}  // namespace bounce
