// What a ray hit: the surface attributes at a Tracer hit, for the G-buffer and the path tracer.
#pragma once

#include "bounce/core/math.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct SurfaceHit {
  vec3 position;
  vec3 normal;            // shading normal, on the side the ray came from
  vec3 geometric_normal;  // face normal, on the side the ray came from
  vec3 albedo;
  vec3 f0;
  vec3 emission;  // radiance emitted back along the ray (0 when the ray hit the back face)
  float roughness;
  uint32_t material;
};

// Evaluates the surface at `hit` for a ray travelling along `direction`.
SurfaceHit surface_at(const Scene& scene, const Hit& hit, vec3 direction);

}  // namespace bounce
