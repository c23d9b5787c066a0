// One light sample's contribution at a surface, before its shadow ray, written without
// branches, for area lights (a sampled point) and punctual lights (point, spot, directional):
// the CPU's direct-light launcher (direct.cpp) runs these across a row of pixels as vector code,
// and direct_pixel calls them once per sample (the GPU, and every scene the row loop does not
// take). They give what area_light_sample or sample_punctual_light followed by
// shade_light_sample gives.
//
// GCC vectorises a row loop over it only if the body is one basic block: every value is computed
// whether or not it is used and the unused ones are selected away (`pick`: so a NaN from a
// degenerate sample never reaches a result), structs are built from scalars rather than copied
// whole, and the file is compiled with -fno-trapping-math -fno-math-errno (src/CMakeLists.txt).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/render/brdf.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/surface_hit.h"
#include "bounce/scene/light.h"

namespace bounce {

// What a lane shades: plain values.
struct LaneSurface {
  vec3 origin;  // the shadow ray's origin: the position offset off the surface
  vec3 normal;
  vec3 geometric_normal;
  vec3 albedo;
  vec3 f0;
  float roughness;
  vec3 wo;  // unit, towards the eye
};

struct LaneSample {
  vec3 wi;         // unit, towards the sampled point
  float distance;  // to the sampled point
  vec3 radiance;   // what reaches the eye if the shadow ray is clear; 0 where nothing can
};

// The lane surface of a G-buffer surface seen from `eye`. (Filled field by field into a named
// value: a braced return is a whole-struct copy to GCC.)
BOUNCE_HD BOUNCE_LANE_INLINE LaneSurface lane_surface(vec3 position, vec3 normal,
                                                      vec3 geometric_normal, vec3 albedo, vec3 f0,
                                                      float roughness, vec3 eye) {
  LaneSurface s;
  s.origin = offset_origin(position, geometric_normal);
  s.normal = normal;
  s.geometric_normal = geometric_normal;
  s.albedo = albedo;
  s.f0 = f0;
  s.roughness = roughness;
  s.wo = glm::normalize(eye - position);
  return s;
}
BOUNCE_HD BOUNCE_LANE_INLINE LaneSurface lane_surface(const SurfaceHit& s, vec3 eye) {
  return lane_surface(s.position, s.normal, s.geometric_normal, s.albedo, s.f0, s.roughness, eye);
}
// The same at G-buffer pixel i, read plane by plane.
BOUNCE_HD BOUNCE_LANE_INLINE LaneSurface lane_surface(const ConstGBufferView& g, size_t i,
                                                      vec3 eye) {
  return lane_surface(load3(g.position, i), load3(g.normal, i), load3(g.geometric_normal, i),
                      load3(g.albedo, i), load3(g.f0, i), g.roughness[i], eye);
}

// The BRDF times the cosine and `weight` (radiance / pdf) and `scale`, for a sample from unit
// direction wi; 0 unless `valid` and wi is in front of both the shading normal and the face.
// Without kGlossy the surface must have no specular lobe (f0 = 0), which then costs nothing: a
// row loop over purely diffuse pixels (a Quake level, the Cornell box) skips the GGX arithmetic
// with the same result (1.3 of a level's 17 ms of direct light).
template <bool kGlossy = true>
BOUNCE_HD BOUNCE_LANE_INLINE vec3 lane_shade(const LaneSurface& s, vec3 wi, vec3 weight,
                                             float scale, bool valid) {
  const float cos_theta = glm::dot(s.normal, wi);
  vec3 f = lambert(s.albedo);
  if constexpr (kGlossy) {
    const float n_dot_v = glm::dot(s.normal, s.wo);
    const vec3 specular =
        ggx_specular_front(s.normal, s.wo, wi, cos_theta, n_dot_v, s.roughness, s.f0);
    const bool glossy = (max_component(s.f0) > 0.0f) & (n_dot_v > 0.0f);
    f = f + pick(glossy, specular, vec3(0.0f));
  }
  const vec3 radiance = f * weight * (cos_theta * scale);
  const bool arrives = valid & (cos_theta > 0.0f) & (glm::dot(s.geometric_normal, wi) > 0.0f);
  return pick(arrives, radiance, vec3(0.0f));
}

// The sample towards point q (front-face normal q_normal) of an area light of `light_radiance`
// and total `light_area`, sampled by area, with the BRDF, both cosines and `scale` applied.
template <bool kGlossy = true>
BOUNCE_HD BOUNCE_LANE_INLINE LaneSample area_light_lane(const LaneSurface& s, vec3 q, vec3 q_normal,
                                                        vec3 light_radiance, float light_area,
                                                        float scale) {
  const vec3 to_light = q - s.origin;
  const float d2 = glm::dot(to_light, to_light);
  const float inv_distance = 1.0f / std::sqrt(d2);
  LaneSample out;
  out.distance = d2 * inv_distance;
  out.wi = to_light * inv_distance;
  const float cos_light = -glm::dot(q_normal, out.wi);
  // radiance / pdf, as area_light_sample weighs it.
  const vec3 weight = light_radiance * ((cos_light * light_area) / d2);
  // In front of the light's face (and, lane_shade checks, of the surface's).
  out.radiance = lane_shade<kGlossy>(s, out.wi, weight, scale, (d2 > 0.0f) & (cos_light > 0.0f));
  return out;
}

// A point, spot or directional light as plain values, made once before a row loop (a select
// between a LightRecord's fields inside the loop would be a masked load GCC does not vectorise).
struct PunctualLane {
  bool directional;
  bool spot;
  vec3 position;   // point, spot
  vec3 direction;  // spot: its axis; directional: the direction light travels
  vec3 power;      // point, spot: intensity, W/sr; directional: irradiance, W/m^2
  float cos_inner, cos_outer;
};

BOUNCE_HD inline PunctualLane punctual_lane(const LightRecord& light) {
  PunctualLane l;
  l.directional = light.type == LightType::kDirectional;
  l.spot = light.type == LightType::kSpot;
  l.position = light.position;
  l.direction = light.direction;
  l.power = l.directional ? light.irradiance : light.intensity;
  l.cos_inner = light.cos_inner;
  l.cos_outer = light.cos_outer;
  return l;
}

// spot_falloff without branches: 1 inside the inner cone, 0 outside the outer, smoothstep
// between.
BOUNCE_HD BOUNCE_LANE_INLINE float spot_falloff_lane(const PunctualLane& l, vec3 dir_from_light) {
  const float c = glm::dot(dir_from_light, l.direction);
  const float t = (c - l.cos_outer) / (l.cos_inner - l.cos_outer);
  return pick(c >= l.cos_inner, 1.0f, pick(c <= l.cos_outer, 0.0f, t * t * (3.0f - 2.0f * t)));
}

// Whether no point within `radius` of `centre` lies inside spot light l's outer cone, so none
// receives its light (spot_falloff_lane is 0 there): the row loop skips the spot for such rows.
// The sphere's distance from the cone's tangent plane along the generator nearest the centre
// bounds its distance from the cone (a convex cone lies behind each tangent plane), so this
// never skips a lit point; a margin of a thousandth of the distances covers rounding. False for
// other lights and for cones wider than a hemisphere (not convex).
BOUNCE_HD inline bool sphere_outside_spot(const PunctualLane& l, vec3 centre, float radius) {
  if (!l.spot || !(l.cos_outer > 0.0f)) return false;
  const vec3 v = centre - l.position;
  const float along = glm::dot(v, l.direction);
  const float across = glm::length(v - along * l.direction);
  const float sin_outer = std::sqrt(glm::max(1.0f - l.cos_outer * l.cos_outer, 0.0f));
  const float beyond = across * l.cos_outer - along * sin_outer;
  return beyond > radius + 1e-3f * (glm::length(v) + radius);
}

// The one sample of punctual light l (sample_punctual_light), with the BRDF, the cosine and
// `scale` applied.
template <bool kGlossy = true>
BOUNCE_HD BOUNCE_LANE_INLINE LaneSample punctual_light_lane(const LaneSurface& s,
                                                            const PunctualLane& l, float scale) {
  const vec3 to_light = l.position - s.origin;
  const float d2 = glm::dot(to_light, to_light);
  const float distance = std::sqrt(d2);
  const vec3 towards = to_light / distance;
  const float falloff = pick(l.spot, spot_falloff_lane(l, -towards), 1.0f);
  LaneSample out;
  out.wi = pick(l.directional, -l.direction, towards);
  out.distance = pick(l.directional, std::numeric_limits<float>::infinity(), distance);
  const vec3 weight = pick(l.directional, l.power, l.power * (falloff / d2));
  out.radiance = lane_shade<kGlossy>(s, out.wi, weight, scale, l.directional | (d2 > 0.0f));
  return out;
}

}  // namespace bounce
