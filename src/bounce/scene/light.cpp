#include "bounce/scene/light.h"

#include <cmath>

namespace bounce {

vec3& Light::emission() {
  switch (type) {
    case LightType::kDirectional:
      return irradiance;
    case LightType::kSphere:
    case LightType::kEnvironment:
      return radiance;
    default:
      return intensity;
  }
}

Light Light::point(vec3 position, vec3 intensity) {
  Light l;
  l.type = LightType::kPoint;
  l.position = position;
  l.intensity = intensity;
  return l;
}

Light Light::spot(vec3 position, vec3 direction, vec3 intensity, float inner_deg, float outer_deg) {
  Light l;
  l.type = LightType::kSpot;
  l.position = position;
  l.direction = glm::normalize(direction);
  l.intensity = intensity;
  l.cos_inner = std::cos(glm::radians(inner_deg));
  l.cos_outer = std::cos(glm::radians(outer_deg));
  return l;
}

Light Light::directional(vec3 direction, vec3 irradiance) {
  Light l;
  l.type = LightType::kDirectional;
  l.direction = glm::normalize(direction);
  l.irradiance = irradiance;
  return l;
}

Light Light::sphere(vec3 centre, float radius, vec3 radiance) {
  Light l;
  l.type = LightType::kSphere;
  l.position = centre;
  l.radius = radius;
  l.radiance = radiance;
  return l;
}

Light Light::environment(vec3 radiance, float rotation_deg) {
  Light l;
  l.type = LightType::kEnvironment;
  l.radiance = radiance;
  l.rotation = glm::radians(rotation_deg);
  return l;
}

const char* Light::type_name() const {
  switch (type) {
    case LightType::kPoint:
      return "point";
    case LightType::kSpot:
      return "spot";
    case LightType::kDirectional:
      return "directional";
    case LightType::kSphere:
      return "sphere";
    case LightType::kEnvironment:
      return "environment";
  }
  return "?";
}

}  // namespace bounce
