// SceneView: the scene as kernels read it. Pointers and counts only (no std::vector, std::string
// or references to host objects), trivially copyable, so a kernel takes it by value and the CUDA
// backend can point it at device copies. SceneData (scene_data.h) owns the arrays it points to.
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/scene/bounds.h"
#include "bounce/scene/environment.h"
#include "bounce/scene/light.h"
#include "bounce/scene/material.h"
#include "bounce/scene/material_eval.h"
#include "bounce/scene/mesh.h"
#include "bounce/scene/texture.h"

namespace bounce {

// One triangle of a mesh.
struct TriangleRef {
  uint32_t mesh = 0;
  uint32_t triangle = 0;
};

// An area light (the emissive triangles of one mesh sharing a material; see AreaLight).
struct AreaLightView {
  vec3 radiance{0.0f};  // emitted radiance, W/(sr m^2)
  float area = 0.0f;    // m^2
  const TriangleRef* triangles = nullptr;
  const vec3* normals = nullptr;  // unit front-face normal of each triangle
  const float* cdf = nullptr;     // cumulative triangle area / total area; the last is 1
  uint32_t triangle_count = 0;

  BOUNCE_HD vec3 power() const { return radiance * (kPi * area); }
};

struct SceneView {
  const MeshView* meshes = nullptr;
  uint32_t mesh_count = 0;
  const uint32_t* triangle_offsets = nullptr;  // global id of each mesh's first triangle
  const MaterialRecord* materials = nullptr;
  uint32_t material_count = 0;
  const TextureView* textures = nullptr;
  uint32_t texture_count = 0;
  const LightRecord* lights = nullptr;
  uint32_t light_count = 0;
  const AreaLightView* area_lights = nullptr;
  uint32_t area_light_count = 0;
  Bounds bounds;
  // The environment light (an entry of `lights`; a scene has at most one), -1 if none, and its
  // map (empty for a uniform sky). Rays that leave the scene see it.
  int32_t environment = -1;
  EnvironmentMapView environment_map;

  // Diffuse albedo of a material at a texture coordinate (as Scene::albedo).
  BOUNCE_HD vec3 albedo(const MaterialRecord& material, vec2 uv) const {
    return material_at(material, textures, uv).albedo;
  }
  // Radiance seen looking along unit direction d past all geometry (0 without an environment).
  BOUNCE_HD vec3 background(vec3 d) const {
    if (environment < 0) return vec3(0.0f);
    return environment_radiance(lights[environment], environment_map, d);
  }
  // Global triangle id (as Scene::triangle_offsets numbers them).
  BOUNCE_HD uint32_t triangle_id(uint32_t mesh, uint32_t triangle) const {
    return triangle_offsets[mesh] + triangle;
  }
};

static_assert(std::is_trivially_copyable_v<SceneView>);
static_assert(std::is_trivially_copyable_v<MeshView>);
static_assert(std::is_trivially_copyable_v<AreaLightView>);
static_assert(std::is_trivially_copyable_v<TextureView>);
static_assert(std::is_trivially_copyable_v<LightRecord>);
static_assert(std::is_trivially_copyable_v<MaterialRecord>);

}  // namespace bounce
