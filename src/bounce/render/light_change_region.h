// Where a change of the scene's lights can change direct light: inside the cones of the spot
// lights that changed, as they were and as they are, or everywhere. The denoiser clips the
// history of direct light only there when nothing but lights changed, so a flashlight carried
// through a level leaves the long averages of the level's still lights alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/scene/light.h"
#include "bounce/scene/scene_change.h"

namespace bounce {

// Whether point p lies in the cone from `apex` around the unit `axis` whose half-angle has the
// cosine `cos_half`.
BOUNCE_HD BOUNCE_LANE_INLINE bool in_cone(vec3 p, vec3 apex, vec3 axis, float cos_half) {
  const vec3 v = p - apex;
  return glm::dot(v, axis) >= cos_half * std::sqrt(glm::dot(v, v));
}

struct LightChangeRegion {
  static constexpr int kMaxCones = 4;  // two spot lights changed, before and after
  bool everywhere = true;
  int cones = 0;
  vec3 apex[kMaxCones];
  vec3 axis[kMaxCones];  // unit
  float cos_outer[kMaxCones];

  static LightChangeRegion all() { return {}; }
  static LightChangeRegion none() {
    LightChangeRegion r;
    r.everywhere = false;
    return r;
  }

  // A spot sends nothing outside its outer cone (spot_falloff), so a point outside every cone
  // kept its direct light.
  BOUNCE_HD bool contains(vec3 p) const {
    bool inside = everywhere;
    for (int k = 0; k < cones; ++k) inside |= in_cone(p, apex[k], axis[k], cos_outer[k]);
    return inside;
  }
};

// The region of `before` -> `after` (the scene's lights at two frames): the outer cones of the
// spot lights that differ, both poses (a pose that sends no light, none: lights_in_history's dark
// records); everywhere when another kind of light changed, the number of lights changed or more
// spots changed than the region holds.
LightChangeRegion light_change_region(std::span<const LightRecord> before,
                                      std::span<const LightRecord> after);

// The point, spot and directional lights that differ between two frames' records (`before` the
// last frame's), which the renderer shades apart from the denoiser's history
// (DirectSettings::apart); none when the light count changed. When more moved than this holds,
// the point and directional lights first (in the history their change would reach every pixel,
// a spot's only its cones), then the most powerful spots; the others stay in the history.
struct LightsApart {
  static constexpr int kMax = 2;
  uint32_t index[kMax] = {};
  int count = 0;

  std::span<const uint32_t> indices() const { return {index, size_t(count)}; }
  bool operator==(const LightsApart& o) const {
    return std::equal(indices().begin(), indices().end(), o.indices().begin(), o.indices().end());
  }
};
LightsApart moved_punctual_lights(std::span<const LightRecord> before,
                                  std::span<const LightRecord> after);

// `lights` as the denoiser's history holds them: those set apart as dark records (the type
// alone, sending no light; the same whatever the pose), so that a light kept apart frame after
// frame changes nothing there, and one going into or out of the history changes its cone.
std::vector<LightRecord> lights_in_history(std::span<const LightRecord> lights,
                                           const LightsApart& apart);

// The region of a frame's `change`, the lights having been `before` at the last frame: the
// lights' region (light_change_region) when nothing but lights changed, else everywhere (moved
// meshes and edited materials change shadows and light anywhere).
LightChangeRegion light_change_region(const SceneChange& change,
                                      std::span<const LightRecord> before,
                                      std::span<const LightRecord> after);

}  // namespace bounce
