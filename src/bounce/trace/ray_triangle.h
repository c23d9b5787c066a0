// Ray against triangle: the test for code that already knows which triangle to try (the primary
// raster's candidates, the brute-force closest hit of technique `vertex`).
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/trace/ray.h"

namespace bounce {

// The ray/triangle test of Moller and Trumbore (1997): whether the ray meets triangle p0 p1 p2
// at a distance in (tmin, tmax); t and the weights of p1 and p2 (Hit::barycentric) where it does.
BOUNCE_HD inline bool intersect_triangle(vec3 p0, vec3 p1, vec3 p2, const Ray& ray, float& t,
                                         vec2& barycentric) {
  const vec3 e1 = p1 - p0, e2 = p2 - p0;
  const vec3 pv = glm::cross(ray.direction, e2);
  const float det = glm::dot(e1, pv);
  if (glm::abs(det) < 1e-12f) return false;
  const float inv = 1.0f / det;
  const vec3 tv = ray.origin - p0;
  const float b1 = glm::dot(tv, pv) * inv;
  if (b1 < 0.0f || b1 > 1.0f) return false;
  const vec3 qv = glm::cross(tv, e1);
  const float b2 = glm::dot(ray.direction, qv) * inv;
  if (b2 < 0.0f || b1 + b2 > 1.0f) return false;
  const float d = glm::dot(e2, qv) * inv;
  if (!(d > ray.tmin && d < ray.tmax)) return false;
  t = d;
  barycentric = vec2(b1, b2);
  return true;
}

}  // namespace bounce
