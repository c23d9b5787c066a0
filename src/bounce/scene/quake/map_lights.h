// Light entities and spawn points of a Quake 3 map, converted to bounce lights and cameras.
#pragma once

#include <optional>
#include <vector>

#include "bounce/scene/camera.h"
#include "bounce/scene/light.h"
#include "bounce/scene/quake/entities.h"

namespace bounce::quake {

struct EntityLights {
  std::vector<Light> lights;
  size_t point = 0, spot = 0, sun = 0;
};

// "light" entities: point lights, spot lights (those with a target) and suns (spots with
// "_sun"), scaled by `scale`. Lights with a missing target stay point lights, as in q3map.
EntityLights entity_lights(const std::vector<Entity>& entities, float scale);

// The spawn points (info_player_deathmatch, else info_player_start), in map order.
std::vector<const Entity*> spawn_points(const std::vector<Entity>& entities);

// The camera of a player standing at a spawn point: eye height, looking along its "angle".
Camera spawn_camera(const Entity& spawn);

}  // namespace bounce::quake
