// Surface material: Lambert diffuse plus a GGX specular lobe (seed 000 §4.3), and emission.
#pragma once

#include <string>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Everything a material is except its name: plain data that kernels copy and read (SceneView).
struct MaterialRecord {
  vec3 albedo{0.8f};        // diffuse albedo, linear RGB in [0, 1]
  int albedo_texture = -1;  // index into Scene::textures; multiplies albedo when >= 0
  float roughness = 1.0f;   // GGX perceptual roughness in [0, 1]; alpha = roughness^2
  vec3 f0{0.0f};            // specular reflectance at normal incidence (0 = purely diffuse)
  vec3 emission{0.0f};      // emitted radiance from the front face, W/(sr m^2)

  BOUNCE_HD bool is_emissive() const { return max_component(emission) > 0.0f; }
  BOUNCE_HD bool has_specular() const { return max_component(f0) > 0.0f; }
};

struct Material : MaterialRecord {
  std::string name;
};

}  // namespace bounce
