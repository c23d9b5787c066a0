// SurfaceHit: the one record of a surface point that light is reflected at. Surfaces at ray hits
// (surface.h), the BRDF and its sampling, direct light, the path tracer and the G-buffer
// (GBufferView::surface / store) all read and write this record, so no stage converts it by hand.
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct SurfaceHit {
  vec3 position{0.0f};
  vec3 normal{0.0f, 0.0f, 1.0f};            // unit shading normal, on the viewer's side
  vec3 geometric_normal{0.0f, 0.0f, 1.0f};  // unit face normal, on the viewer's side
  vec3 albedo{0.0f};                        // diffuse albedo (texture applied)
  vec3 f0{0.0f};                            // specular reflectance at normal incidence
  vec3 emission{0.0f};     // radiance emitted back towards the viewer (0 on back faces)
  float roughness = 1.0f;  // GGX perceptual roughness
};

}  // namespace bounce
