// The scene model every technique renders: meshes, materials, textures, lights and a camera.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bounce/scene/animation.h"
#include "bounce/scene/bounds.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/environment_map.h"
#include "bounce/scene/light.h"
#include "bounce/scene/material.h"
#include "bounce/scene/mesh.h"
#include "bounce/scene/scene_view.h"
#include "bounce/scene/texture.h"

namespace bounce {

// The emissive triangles of one mesh that share a material, sampled as one area light
// (one-sided: they emit from the front face, the side their winding's normal points to).
struct AreaLight {
  std::string name;
  vec3 radiance{0.0f};  // emitted radiance, W/(sr m^2)
  std::vector<TriangleRef> triangles;
  std::vector<vec3> normals;  // unit front-face normal of each triangle
  std::vector<float> cdf;     // cumulative triangle area / total area; cdf.back() == 1
  float area = 0.0f;          // m^2

  vec3 power() const { return radiance * (kPi * area); }
};

struct Scene {
  std::string source;  // file name or built-in name, used in messages
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  // The map of the environment light (a scene has at most one); null for a uniform sky.
  std::shared_ptr<const EnvironmentMap> environment_map;
  Camera camera;
  bool has_camera = false;  // false: finalize() frames the bounds from the front
  Animation animation;      // keyframed meshes and lights, camera path (may be empty)

  // Derived by finalize().
  std::vector<AreaLight> area_lights;
  Bounds bounds;
  std::vector<uint32_t> triangle_offsets;  // global id of each mesh's first triangle

  // Checks every index, number and reference (throws Error naming `source` and the problem),
  // then derives bounds, area lights and, if there is none, a camera.
  void finalize();
  // Re-derives bounds, triangle offsets and area lights from the current meshes and lights:
  // after an edit or animate() (which calls it).
  void derive();
  // Moves another scene's meshes, materials, textures and lights in, transformed by `m`.
  void append(Scene&& other, const mat4& m);

  size_t triangle_count() const;
  // Diffuse albedo of a material at a texture coordinate.
  vec3 albedo(const MaterialRecord& material, vec2 uv) const;
};

}  // namespace bounce
