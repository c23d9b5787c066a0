#include "bounce/trace/ray_sphere.h"

namespace bounce {

float ray_sphere_distance(vec3 centre, float radius, vec3 origin, vec3 direction, float tmin) {
  return ray_sphere_distance_inline(centre, radius, origin, direction, tmin);
}

}  // namespace bounce
