#include "bounce/render/photon_emission.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/sampling.h"

namespace bounce {

PhotonEmitters PhotonEmitters::from(const Scene& scene) {
  PhotonEmitters e;
  e.scene_centre = scene.bounds.centre();
  e.scene_radius = std::max(0.5f * scene.bounds.diagonal(), 1e-3f);
  for (uint32_t i = 0; i < scene.lights.size(); ++i)
    e.entries.push_back({Kind::kLight, i, scene.lights[i].power(e.scene_radius)});
  for (uint32_t i = 0; i < scene.area_lights.size(); ++i)
    e.entries.push_back({Kind::kArea, i, scene.area_lights[i].power()});
  float sum = 0.0f;
  for (const auto& entry : e.entries) {
    sum += entry.power.x + entry.power.y + entry.power.z;
    e.cdf.push_back(sum);
    e.total_power += entry.power;
  }
  if (!(sum > 0.0f)) {
    e.entries.clear();
    e.cdf.clear();
    return e;
  }
  for (float& c : e.cdf) c /= sum;
  e.cdf.back() = 1.0f;
  return e;
}

namespace {

// A uniform point on an area light, picked by area with u.x reused inside the triangle.
void sample_area_point(const Scene& scene, const AreaLight& light, vec2 u, vec3& point,
                       vec3& normal) {
  const auto it = std::lower_bound(light.cdf.begin(), light.cdf.end(), u.x);
  const size_t k = std::min(size_t(it - light.cdf.begin()), light.cdf.size() - 1);
  const float lo = k == 0 ? 0.0f : light.cdf[k - 1];
  const float span = light.cdf[k] - lo;
  const vec2 w(span > 0.0f ? glm::clamp((u.x - lo) / span, 0.0f, 0.99999994f) : 0.5f, u.y);
  const Mesh& mesh = scene.meshes[light.triangles[k].mesh];
  const uint32_t t = light.triangles[k].triangle;
  const uvec3 tri = mesh.triangles[t];
  const vec2 b = sample_uniform_triangle(w);
  point = (1.0f - b.x - b.y) * mesh.positions[tri.x] + b.x * mesh.positions[tri.y] +
          b.y * mesh.positions[tri.z];
  normal = light.normals[k];
}

}  // namespace

EmittedPhoton emit_photon(const Scene& scene, const PhotonEmitters& emitters, vec2 u, vec2 v,
                          uint32_t path_count) {
  // Choose the light with u.x, then stretch u.x back over [0, 1) within its interval.
  const auto it = std::lower_bound(emitters.cdf.begin(), emitters.cdf.end(), u.x);
  const size_t k = std::min(size_t(it - emitters.cdf.begin()), emitters.cdf.size() - 1);
  const float lo = k == 0 ? 0.0f : emitters.cdf[k - 1];
  const float probability = emitters.cdf[k] - lo;
  u.x = glm::clamp((u.x - lo) / probability, 0.0f, 0.99999994f);
  const auto& entry = emitters.entries[k];
  EmittedPhoton p;
  p.flux = entry.power / (probability * float(path_count));

  if (entry.kind == PhotonEmitters::Kind::kArea) {
    vec3 normal;
    sample_area_point(scene, scene.area_lights[entry.index], u, p.origin, normal);
    p.direction = Basis::from_normal(normal).to_world(sample_cosine_hemisphere(v));
    p.origin = offset_origin(p.origin, normal);
    return p;
  }
  const Light& light = scene.lights[entry.index];
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
          glm::max(entry.power.x + entry.power.y + entry.power.z, 1e-30f) /
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
