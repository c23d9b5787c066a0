// TraceView: how kernel bodies ask ray queries. A trivially copyable handle (the acceleration
// structure and the sphere lights) with closest-hit and occlusion queries for single rays. On the
// host its triangle queries go to Embree through out-of-line functions (so Embree's headers stay
// inside trace/) when the view carries an Embree scene, and to our own BVH's traversal otherwise;
// on the device they always go to the BVH (bvh_traversal.h, inline on both sides). Sphere lights
// are geometry: closest hit reports them and they block occlusion rays, exactly as the Tracer's
// calls do.
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/trace/bvh_traversal.h"
#include "bounce/trace/bvh_view.h"
#include "bounce/trace/ray.h"
#include "bounce/trace/ray_sphere.h"

namespace bounce {

// A sphere light as the trace view sees it.
struct TraceSphere {
  vec3 centre{0.0f};
  float radius = 0.0f;
  uint32_t light = 0;  // index into the scene's lights
};

struct TraceView {
  // Host: the Embree scene (RTCScene), or null where the view traces our BVH. Unused on the device.
  const void* triangles = nullptr;
  const TraceSphere* spheres = nullptr;
  uint32_t sphere_count = 0;
  // Our BVH (BvhTracer's view, or its copy on the device); empty for Embree's view.
  BvhView bvh;

  BOUNCE_HD Hit intersect(const Ray& ray) const;
  BOUNCE_HD bool occluded(const Ray& ray) const;
};
static_assert(std::is_trivially_copyable_v<TraceView>);

// Triangles only, on the host (trace/embree_tracer.cpp).
Hit host_intersect_triangles(const void* triangles, const Ray& ray);
bool host_occluded_triangles(const void* triangles, const Ray& ray);

// Distance to the first sphere crossing in (tmin, limit), or infinity.
BOUNCE_HD inline float trace_sphere_distance(const TraceSphere& s, const Ray& ray) {
#if BOUNCE_DEVICE_CODE
  return ray_sphere_distance_inline(s.centre, s.radius, ray.origin, ray.direction, ray.tmin);
#else
  return ray_sphere_distance(s.centre, s.radius, ray.origin, ray.direction, ray.tmin);
#endif
}

// Replaces `hit` with the nearest sphere light in front of it (and within the ray), if any.
BOUNCE_HD inline void closest_sphere(const TraceSphere* spheres, uint32_t count, const Ray& ray,
                                     Hit& hit) {
  float limit = hit.t < ray.tmax ? hit.t : ray.tmax;
  for (uint32_t k = 0; k < count; ++k) {
    const float t = trace_sphere_distance(spheres[k], ray);
    if (t < limit) {
      limit = t;
      hit = Hit{};
      hit.t = t;
      hit.light = spheres[k].light;
    }
  }
}

// Whether a sphere light lies on the ray within (tmin, tmax).
BOUNCE_HD inline bool any_sphere(const TraceSphere* spheres, uint32_t count, const Ray& ray) {
  for (uint32_t k = 0; k < count; ++k)
    if (trace_sphere_distance(spheres[k], ray) < ray.tmax) return true;
  return false;
}

BOUNCE_HD inline Hit TraceView::intersect(const Ray& ray) const {
#if BOUNCE_DEVICE_CODE
  Hit hit = bvh_intersect(bvh, ray);
#else
  Hit hit = triangles ? host_intersect_triangles(triangles, ray) : bvh_intersect(bvh, ray);
#endif
  closest_sphere(spheres, sphere_count, ray, hit);
  return hit;
}

BOUNCE_HD inline bool TraceView::occluded(const Ray& ray) const {
  if (any_sphere(spheres, sphere_count, ray)) return true;
#if BOUNCE_DEVICE_CODE
  return bvh_occluded(bvh, ray);
#else
  return triangles ? host_occluded_triangles(triangles, ray) : bvh_occluded(bvh, ray);
#endif
}

}  // namespace bounce
