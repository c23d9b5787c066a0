#include "bounce/scene/quake/map_lights.h"

#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "bounce/scene/quake/units.h"

namespace bounce::quake {

namespace {

// q3map's defaults: a light without a value is 300; a spot without a radius is 64 units wide
// at its target.
constexpr float kDefaultLight = 300.0f;
constexpr float kDefaultSpotRadius = 64.0f;

vec3 light_colour(const Entity& e) {
  const auto c = e.vector("_color") ? e.vector("_color") : e.vector("color");
  return c ? normalized_colour(*c) : vec3(1.0f);
}

float light_value(const Entity& e) {
  float v = e.number("_light").value_or(e.number("light").value_or(kDefaultLight));
  if (v == 0.0f) v = kDefaultLight;
  if (const auto s = e.number("scale"); s && *s != 0.0f) v *= *s;
  return v;
}

}  // namespace

EntityLights entity_lights(const std::vector<Entity>& entities, float scale) {
  std::unordered_map<std::string, const Entity*> by_name;
  for (const auto& e : entities)
    if (const auto n = e.get("targetname")) by_name.emplace(*n, &e);
  EntityLights out;
  size_t index = 0;
  for (const auto& e : entities) {
    if (e.classname() != "light") continue;
    const auto origin = e.vector("origin");
    if (!origin) continue;  // a light nowhere lights nothing
    const float value = light_value(e);
    const vec3 colour = light_colour(e) * scale;
    const vec3 position = point_from_quake(*origin);
    const std::string name = fmt::format("light{}", index++);
    const Entity* target = nullptr;
    if (const auto t = e.get("target"); t && by_name.count(*t)) target = by_name.at(*t);
    const auto target_origin = target ? target->vector("origin") : std::nullopt;
    if (target_origin) {
      vec3 axis = *target_origin - *origin;
      float distance = glm::length(axis);
      if (distance > 0.0f)
        axis /= distance;
      else
        axis = vec3(0, 0, -1), distance = 64.0f;
      const auto sun_flag = e.number("_sun");
      if (sun_flag && *sun_flag != 0.0f) {
        Light l = Light::directional(direction_from_quake(axis), colour * sun_irradiance(value));
        l.name = name;
        out.lights.push_back(l);
        ++out.sun;
        continue;
      }
      // q3map: the cone's radius at distance d from the light is (radius + 16) * d / distance,
      // fading out over the last 32 units at the target.
      float radius = e.number("radius").value_or(kDefaultSpotRadius);
      if (radius == 0.0f) radius = kDefaultSpotRadius;
      const float outer = glm::degrees(std::atan(std::max(radius + 16.0f, 1.0f) / distance));
      const float inner = std::min(
          glm::degrees(std::atan(std::max(radius - 16.0f, 0.0f) / distance)), outer * 0.99f);
      Light l = Light::spot(position, direction_from_quake(axis), colour * point_intensity(value),
                            inner, std::min(outer, 89.0f));
      l.name = name;
      out.lights.push_back(l);
      ++out.spot;
      continue;
    }
    Light l = Light::point(position, colour * point_intensity(value));
    l.name = name;
    out.lights.push_back(l);
    ++out.point;
  }
  return out;
}

std::vector<const Entity*> spawn_points(const std::vector<Entity>& entities) {
  std::vector<const Entity*> out;
  for (const char* kind : {"info_player_deathmatch", "info_player_start"}) {
    for (const auto& e : entities)
      if (e.classname() == kind && e.vector("origin")) out.push_back(&e);
    if (!out.empty()) break;
  }
  return out;
}

Camera spawn_camera(const Entity& spawn) {
  const vec3 origin = *spawn.vector("origin");
  float yaw = spawn.number("angle").value_or(0.0f), pitch = 0.0f;
  if (const auto angles = spawn.vector("angles")) pitch = angles->x, yaw = angles->y;
  const float y = glm::radians(yaw), p = glm::radians(pitch);
  // Quake's yaw turns anticlockwise from +x seen from above; positive pitch looks down.
  const vec3 forward(std::cos(y) * std::cos(p), std::sin(y) * std::cos(p), -std::sin(p));
  Camera c;
  const vec3 eye = origin + vec3(0.0f, 0.0f, kEyeHeightUnits);
  c.position = point_from_quake(eye);
  c.look_at = point_from_quake(eye + forward * 64.0f);
  c.up = vec3(0.0f, 1.0f, 0.0f);
  c.vfov_deg = kSpawnVerticalFovDeg;
  return c;
}

}  // namespace bounce::quake
