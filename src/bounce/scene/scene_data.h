// SceneData: the host-side owner of what a SceneView points to. The scene's arrays flattened
// (every mesh's vertices in one array, every texture's texels in another, ...), so that a backend
// can copy them to a device as they are. Rebuilt when the scene's layout changes; refreshed
// cheaply (moved vertices, lights, materials) when only the contents change.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"

namespace bounce {

class SceneData {
 public:
  SceneData() = default;
  // Views point into the arrays: moves keep them valid (vectors keep their buffers), copies
  // would not.
  SceneData(const SceneData&) = delete;
  SceneData& operator=(const SceneData&) = delete;
  SceneData(SceneData&&) = default;
  SceneData& operator=(SceneData&&) = default;

  static SceneData from(const Scene& scene);
  // Copies everything from the scene (reusing the arrays' memory).
  void build(const Scene& scene);
  // Catches up with moved meshes (positions and normals only), lights, materials, area lights
  // and bounds; rebuilds instead when the scene's layout (counts) changed. The moved meshes keep
  // their former positions as MeshView::previous_positions; the other meshes have none.
  void refresh(const Scene& scene, std::span<const uint32_t> moved_meshes);
  // Forgets the previous positions: nothing moved since the last frame.
  void forget_motion();

  // Valid until the next build, refresh or destruction.
  SceneView view() const;

  // The flattened arrays a view points into, for a backend that copies them to a device and
  // points a device view at the copies (relocating each pointer by its offset in its array).
  struct Arrays {
    std::span<const MeshView> meshes;
    std::span<const vec3> positions, previous_positions, normals;
    std::span<const vec2> uvs;
    std::span<const uvec3> triangles;
    std::span<const uint32_t> triangle_materials, triangle_offsets;
    std::span<const MaterialRecord> materials;
    std::span<const vec3> texels;
    std::span<const TextureView> textures;
    std::span<const LightRecord> lights;
    std::span<const TriangleRef> area_triangles;
    std::span<const vec3> area_normals;
    std::span<const float> area_cdf;
    std::span<const AreaLightView> area_lights;
  };
  Arrays arrays() const {
    return {meshes_,
            positions_,
            previous_positions_,
            normals_,
            uvs_,
            triangles_,
            triangle_materials_,
            triangle_offsets_,
            materials_,
            texels_,
            textures_,
            lights_,
            area_triangles_,
            area_normals_,
            area_cdf_,
            area_lights_};
  }

 private:
  bool same_layout(const Scene& scene) const;
  void copy_small_arrays(const Scene& scene);  // materials, lights, area lights, bounds
  void copy_vertices(const Scene& scene, uint32_t mesh);
  void point_meshes();

  // Where each mesh's arrays start in the flattened ones. Meshes without normals or uvs take
  // no room in those arrays.
  struct MeshRange {
    size_t first_vertex = 0, first_normal = 0, first_uv = 0, first_triangle = 0;
    uint32_t vertex_count = 0, triangle_count = 0;
    bool normals = false, uvs = false;
  };
  std::vector<MeshRange> ranges_;
  std::vector<MeshView> meshes_;
  std::vector<vec3> positions_;
  std::vector<vec3> previous_positions_;  // same layout; meaningful for meshes that moved
  std::vector<uint8_t> moved_;            // per mesh: moved in the last refresh
  std::vector<vec3> normals_;
  std::vector<vec2> uvs_;
  std::vector<uvec3> triangles_;
  std::vector<vec3> face_normals_;  // per triangle, unit: follows the positions
  std::vector<uint32_t> triangle_materials_;
  std::vector<uint32_t> triangle_offsets_;
  std::vector<MaterialRecord> materials_;
  std::vector<vec3> texels_;
  std::vector<TextureView> textures_;
  std::vector<LightRecord> lights_;
  std::vector<TriangleRef> area_triangles_;
  std::vector<vec3> area_normals_;
  std::vector<float> area_cdf_;
  std::vector<AreaLightView> area_lights_;
  Bounds bounds_;
  std::shared_ptr<const EnvironmentMap> environment_map_;
  int32_t environment_ = -1;
};

}  // namespace bounce
