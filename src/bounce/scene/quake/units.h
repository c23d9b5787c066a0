// Quake's units and frame, and its light values, converted to bounce's.
//
// Length: one Quake unit is taken as one inch, 0.0254 m (a player is 56 units, 1.42 m, tall;
// the common convention for Quake-family maps).
// Frame: Quake is Z-up and right-handed; bounce is Y-up and right-handed. (x, y, z) in Quake goes
// to (x, z, -y): a rotation of -90 degrees about x, so handedness and winding are kept.
// Light: q3map, the light compiler, writes lightmap values on a 0..255 scale, and Quake 3 shows
// them with two overbright bits (r_mapOverBrightBits 2: the lightmap is scaled by 4, through the
// lightmap bytes and the display gamma ramp), so a lightmap value of 255 / 4 shows a texture at
// its full brightness. We take that as a white Lambertian surface reflecting radiance
// 1 W/(sr m^2): irradiance pi W/m^2 per 63.75 lightmap steps. q3map's point lights add
// light * 7500 / d^2 * cos (d in units; pointScale 7500 in q3map and q3map2), which for our
// inverse-square point light is a radiant intensity of
//   I = light * 7500 * (pi / 63.75) * 0.0254^2 W/sr   (about 0.24 W/sr per unit of "light").
// Surface lights add value * 0.75 * (form factor) (q3map2's areaScale 0.25 times its
// formFactorValueScale 3): an emitted radiance of 0.75 * value / 63.75 W/(sr m^2).
// A sun (q3map_sun) adds intensity * cos: irradiance pi * intensity / 63.75 W/m^2.
#pragma once

#include "bounce/core/math.h"

namespace bounce::quake {

constexpr float kMetresPerUnit = 0.0254f;
constexpr float kPointScale = 7500.0f;
constexpr float kLightmapFull = 255.0f / 4.0f;
constexpr float kAreaLightScale = 0.25f * 3.0f;
// The eye above a player's origin (Quake 3's DEFAULT_VIEWHEIGHT) and its default field of view:
// 90 degrees across a 4:3 screen, 73.74 degrees vertically.
constexpr float kEyeHeightUnits = 26.0f;
constexpr float kSpawnVerticalFovDeg = 73.7398f;

inline vec3 direction_from_quake(vec3 q) {
  return {q.x, q.z, -q.y};
}
inline vec3 point_from_quake(vec3 q) {
  return direction_from_quake(q) * kMetresPerUnit;
}

// Radiant intensity (W/sr) of a q3map point or spot light of the given "light" value.
inline float point_intensity(float light) {
  return light * kPointScale * (kPi / kLightmapFull) * kMetresPerUnit * kMetresPerUnit;
}
// Emitted radiance (W/(sr m^2)) of a q3map_surfacelight value.
inline float surface_radiance(float value) {
  return value * kAreaLightScale / kLightmapFull;
}
// Irradiance (W/m^2) of a q3map_sun intensity.
inline float sun_irradiance(float intensity) {
  return intensity * kPi / kLightmapFull;
}

// A colour scaled so that its largest channel is 1 (q3map normalises light colours so); black
// or invalid colours become white.
inline vec3 normalized_colour(vec3 c) {
  const float m = max_component(c);
  return m > 0.0f && is_finite(c) && glm::all(glm::greaterThanEqual(c, vec3(0.0f))) ? c / m
                                                                                    : vec3(1.0f);
}

}  // namespace bounce::quake
