// Where photon paths start: every light (point, spot, directional, sphere, emissive triangles),
// chosen in proportion to power by the same LightPicker the path tracer uses. emit_photon is a
// kernel body over the scene view.
#pragma once

#include <cstdint>
#include <memory>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/sampling.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/light_sampling.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"

namespace bounce {

struct EmittedPhoton {
  vec3 origin;
  vec3 direction;
  vec3 flux;  // W carried by the path
};

// What emission reads besides the scene: the light picker, the disk directional and environment
// lights emit from, and the environment's map.
struct PhotonEmitterView {
  LightPickerView picker;     // entries: the scene's lights, then its area lights
  float scene_radius = 0.0f;  // covers the scene, for directional and environment lights
  vec3 scene_centre{0.0f};
  EnvironmentMapView environment_map;  // empty for a uniform sky or no environment
};
static_assert(std::is_trivially_copyable_v<PhotonEmitterView>);

struct PhotonEmitters {
  LightPicker picker;  // entries: Scene::lights, then Scene::area_lights
  vec3 total_power{0.0f};
  float scene_radius = 0.0f;  // covers the scene, for directional and environment lights
  vec3 scene_centre{0.0f};
  std::shared_ptr<const EnvironmentMap> environment_map;  // null for a uniform sky

  static PhotonEmitters from(const Scene& scene);
  bool empty() const { return picker.empty(); }
  // Valid while this object lives and is not rebuilt.
  PhotonEmitterView view() const {
    return {picker.view(), scene_radius, scene_centre,
            environment_map ? environment_map->view() : EnvironmentMapView{}};
  }
};

// A photon leaving area light `area` at the point u picks, along `local` (a direction about the
// light's normal), carrying `flux`.
BOUNCE_HD inline EmittedPhoton photon_from_area_light(const SceneView& scene,
                                                      const AreaLightView& area, vec2 u, vec3 local,
                                                      vec3 flux) {
  const AreaLightPoint q = sample_area_light_point(scene, area, u);
  EmittedPhoton p;
  p.flux = flux;
  p.direction = Basis::from_normal(q.normal).to_world(local);
  p.origin = offset_origin(q.position, q.normal);
  return p;
}

// A photon leaving scene light `light` carrying `flux`. `local` is its direction in the light's
// own frame: the world's for a point light, about the axis for a spot, about the surface normal
// for a sphere light (a directional light's photons go its way). `u` places the photon: the point
// on a sphere light, or on the disc across the scene, behind it, that a directional light's
// photons start from. An environment light's photons take their direction from u (by the map's
// luminance) and start on the disc of the scene's radius across it, at local's (x, y), a uniform
// disc point when local is cosine-distributed (Malley's method); their flux is weighted by
// radiance / pdf over its mean (the power), so the expected flux stays right. A spot's flux is
// weighted by its falloff over the falloff's mean over the outer cone (power / (intensity * cone
// solid angle)), so the expected flux stays right.
BOUNCE_HD inline EmittedPhoton photon_from_light(const LightRecord& light,
                                                 const PhotonEmitterView& emitters, vec2 u,
                                                 vec3 local, vec3 flux) {
  EmittedPhoton p;
  p.flux = flux;
  switch (light.type) {
    case LightType::kPoint:
      p.origin = light.position;
      p.direction = local;
      break;
    case LightType::kSpot: {
      p.origin = light.position;
      p.direction = Basis::from_normal(light.direction).to_world(local);
      const vec3 power = light.power(emitters.scene_radius);
      const float cone = kTwoPi * (1.0f - light.cos_outer);
      const float mean_falloff =
          glm::max(power.x + power.y + power.z, 1e-30f) /
          glm::max((light.intensity.x + light.intensity.y + light.intensity.z) * cone, 1e-30f);
      p.flux *= spot_falloff(light, p.direction) / mean_falloff;
      break;
    }
    case LightType::kDirectional: {
      const Basis basis = Basis::from_normal(light.direction);
      const vec2 d = sample_concentric_disk(u) * emitters.scene_radius;
      p.origin = emitters.scene_centre + basis.t * d.x + basis.b * d.y -
                 light.direction * (2.0f * emitters.scene_radius);
      p.direction = light.direction;
      break;
    }
    case LightType::kSphere: {
      const vec3 n = sample_uniform_sphere(u);
      p.origin = offset_origin(light.position + n * light.radius, n);
      p.direction = Basis::from_normal(n).to_world(local);
      break;
    }
    case LightType::kEnvironment: {
      const EnvironmentSample e = sample_environment(light, emitters.environment_map, u);
      const float r = emitters.scene_radius;
      p.direction = -e.direction;
      p.origin = emitters.scene_centre + e.direction * (2.0f * r);
      if (!(e.pdf > 0.0f)) {
        p.direction = vec3(0.0f, -1.0f, 0.0f);
        p.flux = vec3(0.0f);
        break;
      }
      const Basis basis = Basis::from_normal(p.direction);
      p.origin += (basis.t * local.x + basis.b * local.y) * r;
      const vec3 mean = e.pdf * (4.0f * kPi) * light.radiance * light.map_mean;
      for (int c = 0; c < 3; ++c) p.flux[c] *= mean[c] > 0.0f ? e.radiance[c] / mean[c] : 0.0f;
      break;
    }
  }
  return p;
}

// Emits path i of n: u (stratified over the paths) picks the light and the point on it, v (random)
// the direction. Flux is normalised so that the paths' expected total equals the lights' power.
BOUNCE_HD inline EmittedPhoton emit_photon(const SceneView& scene,
                                           const PhotonEmitterView& emitters, vec2 u, vec2 v,
                                           uint32_t path_count) {
  // Choose the light with u.x, then stretch u.x back over [0, 1) within its interval.
  const LightPickerView& picker = emitters.picker;
  const uint32_t k = picker.pick(u.x);
  const float probability = picker.pmf[k];
  u.x = picker.remap(k, u.x);
  if (k >= picker.light_count) {
    const AreaLightView& area = scene.area_lights[k - picker.light_count];
    return photon_from_area_light(scene, area, u, sample_cosine_hemisphere(v),
                                  area.power() / (probability * float(path_count)));
  }
  const LightRecord& light = scene.lights[k];
  const vec3 flux = light.power(emitters.scene_radius) / (probability * float(path_count));
  // The direction in the light's own frame: the whole sphere for a point light, the outer cone
  // for a spot, a cosine-weighted hemisphere about a sphere light's surface normal.
  const vec3 local = light.type == LightType::kSpot    ? sample_uniform_cone(u, light.cos_outer)
                     : light.type == LightType::kPoint ? sample_uniform_sphere(u)
                                                       : sample_cosine_hemisphere(v);
  return photon_from_light(light, emitters, u, local, flux);
}

}  // namespace bounce
