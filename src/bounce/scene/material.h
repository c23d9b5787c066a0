// Surface material: Lambert diffuse plus a GGX specular lobe (seed 000 §4.3), and emission, with
// glTF's textures (base colour, metallic-roughness, normal, emissive) and alpha cut-outs.
#pragma once

#include <cstdint>
#include <string>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/scene/texture.h"

namespace bounce {

// How a material's alpha is used (glTF's alphaMode). kBlend is approximated as kMask with a
// cutoff of 0.5: a texel more than half transparent is a hole, the rest is opaque (we trace no
// partial transparency).
enum class AlphaMode : uint8_t { kOpaque, kMask, kBlend };

// Everything a material is except its name: plain data that kernels copy and read (SceneView).
// Texture indices name Scene::textures (-1: none); each texture reads the mesh's uv through its
// own transform (KHR_texture_transform; identity otherwise).
struct MaterialRecord {
  vec3 albedo{0.8f};        // diffuse albedo, linear RGB in [0, 1]
  int albedo_texture = -1;  // multiplies albedo when >= 0 (and base_colour in the glTF workflow)
  float roughness = 1.0f;   // GGX perceptual roughness in [0, 1]; alpha = roughness^2
  vec3 f0{0.0f};            // specular reflectance at normal incidence (0 = purely diffuse)
  vec3 emission{0.0f};      // emitted radiance from the front face, W/(sr m^2)
  TextureTransform albedo_transform;

  // glTF's metallic-roughness workflow, kept so that textures can vary metallic per texel: the
  // albedo and f0 above are its values at the untextured factors (what texture-blind readers
  // see); surfaces recompute them from these per hit (material_eval.h).
  bool metallic_workflow = false;
  float metallic = 0.0f;         // metallicFactor
  vec3 base_colour{0.0f};        // baseColorFactor (rgb)
  vec3 dielectric_f0{0.04f};     // F0 of the non-metal part (KHR_materials_specular applied)
  int metal_rough_texture = -1;  // linear; green scales roughness, blue scales metallic
  TextureTransform metal_rough_transform;

  int normal_texture = -1;  // linear tangent-space normal map (glTF: +x along +u, +y up)
  float normal_scale = 1.0f;
  TextureTransform normal_transform;

  int emission_texture = -1;  // sRGB; multiplies emission where a ray sees the surface
  TextureTransform emission_transform;
  // The emission texture's mean texel: area lights (light sampling, photon emission) emit
  // emission * this uniformly over their triangles, the same power as the texture spread out.
  vec3 emission_texture_mean{1.0f};

  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha = 1.0f;         // baseColorFactor's alpha
  float alpha_cutoff = 0.5f;  // kMask: alpha below this is a hole
  int alpha_texture = -1;     // the base colour image's alpha (every channel), read as albedo is

  BOUNCE_HD bool is_emissive() const { return max_component(emission) > 0.0f; }
  BOUNCE_HD bool has_specular() const { return max_component(f0) > 0.0f; }
  // Whether rays can pass through parts of the surface (see material_eval.h's cut_away).
  BOUNCE_HD bool has_cutouts() const { return alpha_mode != AlphaMode::kOpaque; }
};

struct Material : MaterialRecord {
  std::string name;
};

}  // namespace bounce
