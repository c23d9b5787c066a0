#include "bounce/techniques/lhb/lhb_tracer.h"

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"

namespace bounce {

Hit LhbTracer::intersect(const Ray& ray) const {
  return buffers_.closest_hit(ray, nearest_(glm::normalize(ray.direction)));
}

void LhbTracer::intersect(std::span<const Ray> rays, std::span<Hit> hits) const {
  if (rays.size() != hits.size())
    fail("LhbTracer: {} rays but room for {} hits", rays.size(), hits.size());
  parallel_for(
      rays.size(), [&](size_t i) { hits[i] = intersect(rays[i]); }, 1024);
}

}  // namespace bounce
