// Light sources. Emissive triangles are lights too: Scene derives them from materials.
#pragma once

#include <string>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

enum class LightType { kPoint, kSpot, kDirectional, kSphere, kEnvironment };

// Point, spot and directional lights: one deterministic sample each, from a single point or
// direction (sample_punctual_light).
BOUNCE_HD inline bool is_punctual(LightType t) {
  return t == LightType::kPoint || t == LightType::kSpot || t == LightType::kDirectional;
}

// Everything a light is except its name: plain data that kernels copy and read (SceneView).
struct LightRecord {
  LightType type = LightType::kPoint;
  vec3 position{0.0f};       // point, spot, sphere (centre)
  vec3 direction{0, -1, 0};  // spot: the axis it shines along; directional: travel direction
  vec3 intensity{0.0f};      // point, spot: radiant intensity, W/sr
  vec3 irradiance{0.0f};     // directional: irradiance on a surface facing it, W/m^2
  vec3 radiance{0.0f};       // sphere: emitted radiance of its surface, W/(sr m^2); environment:
                             // the sky's radiance, or the factor its map is multiplied by
  vec3 map_mean{1.0f};       // environment: the map's mean over the sphere (1 without a map)
  float rotation = 0.0f;     // environment: radians about +y (scene/environment.h)
  float radius = 0.0f;       // sphere
  float cos_inner = 1.0f;    // spot: full intensity inside this cone
  float cos_outer = 0.0f;    // spot: no light outside this cone (smoothstep between)

  bool operator==(const LightRecord&) const = default;

  // Radiant power in W per channel. A directional light's power depends on the area it lights:
  // scene_radius is the radius of a disk that covers the scene.
  BOUNCE_HD vec3 power(float scene_radius) const {
    switch (type) {
      case LightType::kPoint:
        return intensity * (4.0f * kPi);
      case LightType::kSpot:
        // The smoothstep in cos(theta) integrates to half the width of its band.
        return intensity * (kTwoPi * (1.0f - 0.5f * (cos_inner + cos_outer)));
      case LightType::kDirectional:
        return irradiance * (kPi * scene_radius * scene_radius);
      case LightType::kSphere:
        return radiance * (kPi * 4.0f * kPi * radius * radius);
      case LightType::kEnvironment:
        // The flux through a disc of the scene's radius across every direction (what its
        // photons carry): pi r^2 times the radiance integrated over the sphere.
        return radiance * map_mean * (4.0f * kPi * kPi * scene_radius * scene_radius);
    }
    return vec3(0.0f);
  }
};

struct Light : LightRecord {
  std::string name;

  bool operator==(const Light&) const = default;

  static Light point(vec3 position, vec3 intensity);
  static Light spot(vec3 position, vec3 direction, vec3 intensity, float inner_deg,
                    float outer_deg);
  static Light directional(vec3 direction, vec3 irradiance);
  static Light sphere(vec3 centre, float radius, vec3 radiance);
  // A sky of `radiance` from every direction, or the factor on the scene's environment map
  // (Scene::environment_map), turned by rotation_deg about +y.
  static Light environment(vec3 radiance, float rotation_deg = 0.0f);

  // The colour that sets this light's brightness: intensity (point, spot), irradiance
  // (directional) or radiance (sphere, environment).
  vec3& emission();
  const vec3& emission() const { return const_cast<Light*>(this)->emission(); }
  const char* type_name() const;
};

// The spot's angular falloff: 1 inside the inner cone, 0 outside the outer, smooth between.
BOUNCE_HD inline float spot_falloff(const LightRecord& l, vec3 dir_from_light) {
  const float c = glm::dot(dir_from_light, l.direction);
  if (c >= l.cos_inner) return 1.0f;
  if (c <= l.cos_outer) return 0.0f;
  const float t = (c - l.cos_outer) / (l.cos_inner - l.cos_outer);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace bounce
