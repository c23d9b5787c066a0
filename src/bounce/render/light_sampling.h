// Sampling the light arriving at a surface point from each kind of light. Plain functions over
// plain data, shared by the direct-light stage, the path tracer and (later) CUDA kernels.
#pragma once

#include <cmath>
#include <limits>

#include "bounce/core/cdf_sampling.h"
#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/sampling.h"
#include "bounce/render/brdf.h"
#include "bounce/render/sphere_cone.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

// Light arriving at p from one sample: the contribution to outgoing radiance is
// f(wo, wi) * cos(n, wi) * weight, if a shadow ray from p along wi over `distance` is clear.
struct LightSample {
  vec3 wi{0.0f};  // unit direction towards the light
  float distance = 0.0f;
  vec3 weight{0.0f};  // radiance / pdf (solid angle), or I / d^2, or E for a directional light
  float pdf = 0.0f;   // solid-angle pdf of wi; 0 for point, spot and directional lights

  BOUNCE_HD bool valid() const { return max_component(weight) > 0.0f; }
};

// The shadow ray that tests a light sample from `origin` (a surface point already offset off its
// surface): it stops just short of the sampled point, so the light's own surface (an emissive
// triangle, a sphere light) does not block it. Direct light and the path tracer both use it.
BOUNCE_HD inline Ray shadow_ray(vec3 origin, vec3 wi, float distance) {
  return Ray{origin, 0.0f, wi, distance * (1.0f - 1e-4f)};
}
BOUNCE_HD inline Ray shadow_ray(vec3 origin, const LightSample& ls) {
  return shadow_ray(origin, ls.wi, ls.distance);
}

// Point, spot and directional lights: one deterministic sample.
BOUNCE_HD inline LightSample sample_punctual_light(const LightRecord& light, vec3 p) {
  LightSample s;
  if (light.type == LightType::kDirectional) {
    s.wi = -light.direction;
    s.distance = std::numeric_limits<float>::infinity();
    s.weight = light.irradiance;
    return s;
  }
  const vec3 to_light = light.position - p;
  const float d2 = glm::dot(to_light, to_light);
  if (d2 <= 0.0f) return s;
  s.distance = glm::sqrt(d2);
  s.wi = to_light / s.distance;
  s.weight = light.intensity / d2;
  if (light.type == LightType::kSpot) s.weight *= spot_falloff(light, -s.wi);
  return s;
}

// Sphere light: a direction uniform in the cone the sphere subtends (exact solid-angle pdf).
BOUNCE_HD inline LightSample sample_sphere_light(const LightRecord& light, vec3 p, vec2 u) {
  LightSample s;
  const vec3 to_centre = light.position - p;
  const float d2 = glm::dot(to_centre, to_centre);
  const float r2 = light.radius * light.radius;
  const SphereCone cone = sphere_cone(d2, r2);
  if (!cone.outside) return s;  // inside the light: it is not a surface we shade against
  const float d = glm::sqrt(d2);
  const vec3 local = sample_uniform_cone(u, cone.cos_max);
  s.wi = Basis::from_normal(to_centre / d).to_world(local);
  const float b = glm::dot(s.wi, to_centre);
  s.distance = b - glm::sqrt(glm::max(0.0f, b * b - (d2 - r2)));
  s.pdf = 1.0f / cone.solid_angle();
  s.weight = light.radiance / s.pdf;
  return s;
}

// Environment light: a direction drawn by the map's luminance (uniform for a sky colour), from
// infinitely far away.
BOUNCE_HD inline LightSample sample_environment_light(const SceneView& scene,
                                                      const LightRecord& light, vec2 u) {
  LightSample s;
  const EnvironmentSample e = sample_environment(light, scene.environment_map, u);
  if (!(e.pdf > 0.0f)) return s;
  s.wi = e.direction;
  s.distance = std::numeric_limits<float>::infinity();
  s.pdf = e.pdf;
  s.weight = e.radiance / e.pdf;
  return s;
}

// A uniform point on an area light: u.x picks a triangle by area (and is reused inside it, which
// keeps stratification), then a uniform point on that triangle. Also its front-face normal.
struct AreaLightPoint {
  vec3 position;
  vec3 normal;
};

// The triangle of an area light that u.x picks from its area cdf (core/cdf_sampling.h), and u
// with u.x stretched back over [0, 1) within that triangle's interval.
struct AreaLightTriangle {
  uint32_t index;
  vec2 v;
};
BOUNCE_HD inline AreaLightTriangle pick_area_light_triangle(const float* cdf, uint32_t count,
                                                            vec2 u) {
  const CdfSample pick = sample_cdf(cdf, count, u.x);
  return {pick.entry, vec2(pick.u, u.y)};
}

// A uniform point on triangle (p0, p1, p2) from v in [0, 1)^2.
BOUNCE_HD inline vec3 point_on_triangle(vec3 p0, vec3 p1, vec3 p2, vec2 v) {
  const vec2 b = sample_uniform_triangle(v);
  return (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
}

// The point at `pick` (pick_area_light_triangle's) on the area light's picked triangle.
template <typename Meshes>
BOUNCE_HD inline AreaLightPoint area_light_point_at(const Meshes& meshes,
                                                    const TriangleRef* triangles,
                                                    const vec3* normals, AreaLightTriangle pick) {
  const TriangleRef ref = triangles[pick.index];
  const auto& mesh = meshes[ref.mesh];
  const uvec3 tri = mesh.triangles[ref.triangle];
  return {point_on_triangle(mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z],
                            pick.v),
          normals[pick.index]};
}
// The one implementation behind both forms below: `meshes` is the scene's meshes (host Mesh or
// MeshView; both index positions and triangles alike), the rest the area light's arrays.
template <typename Meshes>
BOUNCE_HD inline AreaLightPoint area_light_point_on(const Meshes& meshes,
                                                    const TriangleRef* triangles,
                                                    const vec3* normals, const float* cdf,
                                                    uint32_t count, vec2 u) {
  return area_light_point_at(meshes, triangles, normals, pick_area_light_triangle(cdf, count, u));
}
BOUNCE_HD inline AreaLightPoint sample_area_light_point(const SceneView& scene,
                                                        const AreaLightView& light, vec2 u) {
  return area_light_point_on(scene.meshes, light.triangles, light.normals, light.cdf,
                             light.triangle_count, u);
}
inline AreaLightPoint sample_area_light_point(const Scene& scene, const AreaLight& light, vec2 u) {
  return area_light_point_on(scene.meshes, light.triangles.data(), light.normals.data(),
                             light.cdf.data(), uint32_t(light.cdf.size()), u);
}

// Area light made of emissive triangles, sampled by area: the sample towards point q of a light
// of `radiance` and total `area`. One-sided emission.
BOUNCE_HD inline LightSample area_light_sample(const AreaLightPoint& q, vec3 radiance, float area,
                                               vec3 p) {
  LightSample s;
  const vec3 to_light = q.position - p;
  const float d2 = glm::dot(to_light, to_light);
  if (d2 <= 0.0f) return s;
  // One reciprocal square root and two divisions (this runs for every pixel's light sample).
  const float inv_distance = 1.0f / glm::sqrt(d2);
  s.distance = d2 * inv_distance;
  s.wi = to_light * inv_distance;
  const float cos_light = -glm::dot(q.normal, s.wi);
  if (cos_light <= 0.0f) return s;  // behind the emitting face
  const float projected = cos_light * area;
  s.pdf = d2 / projected;
  s.weight = radiance * (projected / d2);  // radiance / pdf
  return s;
}
BOUNCE_HD inline LightSample sample_area_light(const SceneView& scene, const AreaLightView& light,
                                               vec3 p, vec2 u) {
  return area_light_sample(sample_area_light_point(scene, light, u), light.radiance, light.area, p);
}
inline LightSample sample_area_light(const Scene& scene, const AreaLight& light, vec3 p, vec2 u) {
  return area_light_sample(sample_area_light_point(scene, light, u), light.radiance, light.area, p);
}

// A sample of one entry of a light list ordered as LightPicker's (render/light_picker.h): the
// scene's lights (0 .. light_count - 1), then its area lights. `delta`: a point, spot or
// directional light, whose one sample no BSDF sampling could find.
struct EntrySample {
  LightSample ls;
  bool delta = false;
};
BOUNCE_HD inline EntrySample sample_light_entry(const SceneView& scene, uint32_t light_count,
                                                uint32_t entry, vec3 p, vec2 u) {
  if (entry >= light_count)
    return {sample_area_light(scene, scene.area_lights[entry - light_count], p, u), false};
  const LightRecord& light = scene.lights[entry];
  if (light.type == LightType::kSphere) return {sample_sphere_light(light, p, u), false};
  if (light.type == LightType::kEnvironment)
    return {sample_environment_light(scene, light, u), false};
  return {sample_punctual_light(light, p), true};
}

// Unshadowed GGX specular from a sphere light by Karis' representative point with the widened
// lobe's energy normalisation (seed 000 §5.2.1, Listings 5.1-5.2). Returns outgoing radiance.
BOUNCE_HD inline vec3 sphere_light_specular(const LightRecord& light, const SurfaceHit& s, vec3 p,
                                            vec3 wo) {
  if (max_component(s.f0) <= 0.0f) return vec3(0.0f);
  const vec3 l = light.position - p;
  const float distance = glm::length(l);
  if (distance <= light.radius) return vec3(0.0f);
  const vec3 r = glm::reflect(-wo, s.normal);
  const vec3 centre_to_ray = glm::dot(l, r) * r - l;
  const float ctr_len = glm::length(centre_to_ray);
  const vec3 rep =
      l + centre_to_ray * (ctr_len > 0.0f ? glm::clamp(light.radius / ctr_len, 0.0f, 1.0f) : 0.0f);
  const vec3 wi = glm::normalize(rep);
  const float n_dot_l = glm::dot(s.normal, wi);
  if (n_dot_l <= 0.0f) return vec3(0.0f);
  const float a = sqr(glm::max(s.roughness, kMinRoughness));
  const float aa = glm::clamp(a + light.radius / (2.0f * distance), 0.0f, 1.0f);
  const float normalisation = sqr(a / aa);
  // The sphere seen as a point: intensity = radiance * projected area.
  const vec3 intensity = light.radiance * (kPi * light.radius * light.radius);
  return ggx_specular(s.normal, wo, wi, s.roughness, s.f0) * intensity * n_dot_l * normalisation /
         sqr(distance);
}

}  // namespace bounce
