#include "bounce/trace/tracer.h"

namespace bounce {

std::vector<TraceSphere> trace_spheres(const Scene& scene) {
  std::vector<TraceSphere> spheres;
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.type == LightType::kSphere) spheres.push_back({l.position, l.radius, i});
  }
  return spheres;
}

}  // namespace bounce
