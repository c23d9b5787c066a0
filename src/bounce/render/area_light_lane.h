// One area-light sample's contribution at a surface, before its shadow ray, written without
// branches: the CPU's direct-light launcher (direct.cpp) runs it across a row of pixels as
// vector code, and direct_pixel calls it once per sample (the GPU, and every scene the row loop
// does not take). It gives what area_light_sample followed by shade_light_sample gives.
//
// GCC vectorises a row loop over it only if the body is one basic block: every value is computed
// whether or not it is used and the unused ones are selected away (`pick`: so a NaN from a
// degenerate sample never reaches a result), structs are built from scalars rather than copied
// whole, and the file is compiled with -fno-trapping-math -fno-math-errno (src/CMakeLists.txt).
#pragma once

#include <cmath>
#include <cstddef>

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/render/brdf.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/render/surface_hit.h"

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

// The sample towards point q (front-face normal q_normal) of an area light of `light_radiance`
// and total `light_area`, sampled by area, with the BRDF, both cosines and `scale` applied.
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
  const float cos_theta = glm::dot(s.normal, out.wi);
  const float n_dot_v = glm::dot(s.normal, s.wo);
  // radiance / pdf, as area_light_sample weighs it.
  const vec3 weight = light_radiance * ((cos_light * light_area) / d2);
  const vec3 specular =
      ggx_specular_front(s.normal, s.wo, out.wi, cos_theta, n_dot_v, s.roughness, s.f0);
  const bool glossy = (max_component(s.f0) > 0.0f) & (n_dot_v > 0.0f);
  const vec3 f = lambert(s.albedo) + pick(glossy, specular, vec3(0.0f));
  const vec3 radiance = f * weight * (cos_theta * scale);
  // In front of the light's face and of the surface's (the shading normal and the face itself).
  const bool arrives = (d2 > 0.0f) & (cos_light > 0.0f) & (cos_theta > 0.0f) &
                       (glm::dot(s.geometric_normal, out.wi) > 0.0f);
  out.radiance = pick(arrives, radiance, vec3(0.0f));
  return out;
}

}  // namespace bounce
