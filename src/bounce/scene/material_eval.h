// A material at one point of a surface: its textures read at the point's uv. Written once for
// the host (over Scene::textures) and kernels (over SceneView::textures): `textures[i]` only has
// to have sample(uv).
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/scene/material.h"

namespace bounce {

struct MaterialPoint {
  vec3 albedo{0.0f};
  vec3 f0{0.0f};
  float roughness = 1.0f;
  vec3 emission{0.0f};  // front-face emission
};

// Inlined (as TextureView::sample is): out of line, its vec3 came back in two registers that the
// caller stored and reloaded as one, a load that waits for every earlier store to drain (the
// G-buffer's writes to memory); 0.45 ms of a level's G-buffer at 640x360. kFiltered: filtered
// over a footprint `uv_width` wide in the material's texture coordinates (TextureView's
// lookup over its chain of levels), else level 0 at the point (a path tracer's many samples filter
// it).
template <bool kFiltered = false, typename Textures>
BOUNCE_HD BOUNCE_LANE_INLINE vec3 texture_at(const Textures& textures, int index,
                                             const TextureTransform& transform, vec2 uv,
                                             float uv_width = 0.0f) {
  if constexpr (kFiltered)
    return textures[index].sample(transform.apply(uv), uv_width * transform.scale());
  else
    return textures[index].sample(transform.apply(uv));
}

// A texture's value at uv, or with kMean its mean (TextureView::mean): a lookup that stands for
// the whole texture.
template <bool kMean, bool kFiltered = false, typename Textures>
BOUNCE_HD BOUNCE_LANE_INLINE vec3 texture_or_mean(const Textures& textures, int index,
                                                  const TextureTransform& transform, vec2 uv,
                                                  float uv_width = 0.0f) {
  if constexpr (kMean)
    return textures[index].mean;
  else
    return texture_at<kFiltered>(textures, index, transform, uv, uv_width);
}

// Which of a material's textures and workflow a loop knows before it starts (material_at's
// kForm): where `known`, these stand for the record's own, so that a loop over the pixels of one
// material has no branch and vectorises (the G-buffer's runs over one triangle). Unknown (the
// default), the record is read.
struct MaterialForm {
  bool known = false;
  bool albedo_texture = false;
  bool metallic = false;  // the metallic-roughness workflow
  bool metal_rough_texture = false;
  bool emission_texture = false;

  BOUNCE_HD static constexpr MaterialForm of(const MaterialRecord& m) {
    return {true, m.albedo_texture >= 0, m.metallic_workflow, m.metal_rough_texture >= 0,
            m.emission_texture >= 0};
  }
  BOUNCE_HD constexpr bool has_albedo_texture(const MaterialRecord& m) const {
    return known ? albedo_texture : m.albedo_texture >= 0;
  }
  BOUNCE_HD constexpr bool is_metallic(const MaterialRecord& m) const {
    return known ? metallic : m.metallic_workflow;
  }
  BOUNCE_HD constexpr bool has_metal_rough_texture(const MaterialRecord& m) const {
    return known ? metal_rough_texture : m.metal_rough_texture >= 0;
  }
  BOUNCE_HD constexpr bool has_emission_texture(const MaterialRecord& m) const {
    return known ? emission_texture : m.emission_texture >= 0;
  }
  constexpr bool operator==(const MaterialForm&) const = default;
};

// The material at uv. kMeanTextures: each texture's mean instead of its texels (photon hits of
// technique `vertex`, which the seed reflects with a texture's average colour: no texel to fetch
// from a random place in memory). Inlined, as texture_at is: out of line, its MaterialPoint
// went back through memory (a level's G-buffer at 1280 x 720: median 37.6 -> 36.0 ms over eight
// alternated runs each; docs/benchmarks.md).
// kFiltered, uv_width: texture_at's.
template <bool kMeanTextures = false, MaterialForm kForm = MaterialForm{}, bool kFiltered = false,
          typename Textures>
BOUNCE_HD BOUNCE_LANE_INLINE MaterialPoint material_at(const MaterialRecord& m,
                                                       const Textures& textures, vec2 uv,
                                                       float uv_width = 0.0f) {
  MaterialPoint p;
  const vec3 tint = kForm.has_albedo_texture(m)
                        ? texture_or_mean<kMeanTextures, kFiltered>(
                              textures, m.albedo_texture, m.albedo_transform, uv, uv_width)
                        : vec3(1.0f);
  p.roughness = m.roughness;
  if (kForm.is_metallic(m)) {
    // glTF: the metallic-roughness texture's green scales roughness and its blue metallic; a
    // metal's base colour is its specular colour, a dielectric's its diffuse albedo.
    float metallic = m.metallic;
    if (kForm.has_metal_rough_texture(m)) {
      const vec3 mr = texture_or_mean<kMeanTextures, kFiltered>(
          textures, m.metal_rough_texture, m.metal_rough_transform, uv, uv_width);
      p.roughness = glm::clamp(p.roughness * mr.y, 0.0f, 1.0f);
      metallic = glm::clamp(metallic * mr.z, 0.0f, 1.0f);
    }
    const vec3 base = m.base_colour * tint;
    p.albedo = base * (1.0f - metallic);
    p.f0 = glm::mix(m.dielectric_f0, base, metallic);
  } else {
    p.albedo = m.albedo * tint;
    p.f0 = load3(m.f0);  // (load3: lane.h)
  }
  p.emission = load3(m.emission);
  if (kForm.has_emission_texture(m))
    p.emission *= texture_or_mean<kMeanTextures, kFiltered>(textures, m.emission_texture,
                                                            m.emission_transform, uv, uv_width);
  return p;
}

// Base colour alpha times the texture's alpha.
template <typename Textures>
BOUNCE_HD float material_alpha(const MaterialRecord& m, const Textures& textures, vec2 uv) {
  if (m.alpha_texture < 0) return m.alpha;
  return m.alpha * texture_at(textures, m.alpha_texture, m.albedo_transform, uv).x;
}

// Whether the surface is a hole at uv, where every ray (primary, shadow, photon) passes on.
template <typename Textures>
BOUNCE_HD bool cut_away(const MaterialRecord& m, const Textures& textures, vec2 uv) {
  if (!m.has_cutouts()) return false;
  const float cutoff = m.alpha_mode == AlphaMode::kMask ? m.alpha_cutoff : 0.5f;
  return material_alpha(m, textures, uv) < cutoff;
}

// The normal map's tangent-space normal at uv (unnormalised, normal_scale applied to x and y,
// as glTF defines it), or (0, 0, 1) without a normal map.
template <typename Textures>
BOUNCE_HD vec3 tangent_space_normal(const MaterialRecord& m, const Textures& textures, vec2 uv) {
  if (m.normal_texture < 0) return vec3(0.0f, 0.0f, 1.0f);
  const vec3 t = texture_at(textures, m.normal_texture, m.normal_transform, uv) * 2.0f - 1.0f;
  return vec3(t.x * m.normal_scale, t.y * m.normal_scale, t.z);
}

}  // namespace bounce
