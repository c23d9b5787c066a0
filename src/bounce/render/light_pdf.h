// The solid-angle pdfs that match light_sampling.h's samplers, for weighting a direction found by
// another strategy (BSDF sampling) with multiple importance sampling.
#pragma once

#include <cmath>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/sphere_cone.h"
#include "bounce/scene/light.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"

namespace bounce {

// pdf with which sample_sphere_light(light, p, .) returns any direction inside the cone the
// sphere subtends from p (uniform in that cone); 0 when p is inside the sphere.
BOUNCE_HD inline float sphere_light_pdf(const LightRecord& light, vec3 p) {
  const vec3 to_centre = light.position - p;
  const SphereCone cone = sphere_cone(glm::dot(to_centre, to_centre), light.radius * light.radius);
  return cone.outside ? 1.0f / cone.solid_angle() : 0.0f;
}

// pdf with which sample_environment_light returns unit direction d (0 without an environment).
BOUNCE_HD inline float environment_light_pdf(const SceneView& scene, vec3 d) {
  if (scene.environment < 0) return 0.0f;
  return environment_pdf(scene.lights[scene.environment], scene.environment_map, d);
}

// pdf with which sample_area_light(scene, light, p, .) returns the direction towards a point of
// the light at `distance` from p whose emitting face makes cosine `cos_light` with the direction
// back to p: the sampler is uniform over the light's area, so this is distance^2 / (cos * area).
BOUNCE_HD inline float area_light_pdf(float area, float distance, float cos_light) {
  if (cos_light <= 0.0f || area <= 0.0f) return 0.0f;
  return distance * distance / (cos_light * area);
}
BOUNCE_HD inline float area_light_pdf(const AreaLightView& light, float distance, float cos_light) {
  return area_light_pdf(light.area, distance, cos_light);
}
inline float area_light_pdf(const AreaLight& light, float distance, float cos_light) {
  return area_light_pdf(light.area, distance, cos_light);
}

}  // namespace bounce
