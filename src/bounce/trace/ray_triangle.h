// Ray against triangle: the test for code that already knows which triangle to try (the primary
// raster's candidates, the brute-force closest hit of technique `vertex`).
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/trace/ray.h"

namespace bounce {

// The ray/triangle test of Moller and Trumbore (1997) for rays from one origin: what depends
// only on the triangle and the origin (both edges, the origin's offset from p0 and its cross
// product with the first edge) made once, so that each ray of a pixel run from the camera pays
// for one cross product and a division (the G-buffer's raster candidates).
struct TriangleFromOrigin {
  vec3 e1, e2, tv, qv;
  float tq;  // dot(e2, qv): the hit distance times the determinant

  BOUNCE_HD static TriangleFromOrigin make(vec3 p0, vec3 p1, vec3 p2, vec3 origin) {
    TriangleFromOrigin f;
    f.e1 = p1 - p0;
    f.e2 = p2 - p0;
    f.tv = origin - p0;
    f.qv = glm::cross(f.tv, f.e1);
    f.tq = glm::dot(f.e2, f.qv);
    return f;
  }

  // Whether a ray from the origin along `direction` meets the triangle at a distance in
  // (tmin, tmax), without a branch: t and the weights of p1 and p2 (Hit::barycentric) are
  // written either way, meaningful where it does (a loop over a run of pixels vectorises).
  BOUNCE_HD BOUNCE_LANE_INLINE bool meets(vec3 direction, float tmin, float tmax, float& t,
                                          vec2& barycentric) const {
    const vec3 pv = glm::cross(direction, e2);
    const float det = glm::dot(e1, pv);
    const float inv = 1.0f / det;
    const float b1 = glm::dot(tv, pv) * inv;
    const float b2 = glm::dot(direction, qv) * inv;
    t = tq * inv;
    barycentric = vec2(b1, b2);
    return (glm::abs(det) >= 1e-12f) & (b1 >= 0.0f) & (b1 <= 1.0f) & (b2 >= 0.0f) &
           (b1 + b2 <= 1.0f) & (t > tmin) & (t < tmax);
  }

  // The same, writing t and the weights only where it meets the triangle.
  BOUNCE_HD bool intersect(vec3 direction, float tmin, float tmax, float& t,
                           vec2& barycentric) const {
    float d;
    vec2 b;
    if (!meets(direction, tmin, tmax, d, b)) return false;
    t = d;
    barycentric = b;
    return true;
  }
};

// The same test for one ray: whether it meets triangle p0 p1 p2 at a distance in (tmin, tmax).
BOUNCE_HD inline bool intersect_triangle(vec3 p0, vec3 p1, vec3 p2, const Ray& ray, float& t,
                                         vec2& barycentric) {
  return TriangleFromOrigin::make(p0, p1, p2, ray.origin)
      .intersect(ray.direction, ray.tmin, ray.tmax, t, barycentric);
}

}  // namespace bounce
