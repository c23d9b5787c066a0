// Cutouts: the host's copy of what CutoutView reads (cutout_view.h), taken from a scene: the uvs,
// triangles and materials of meshes with cut-out materials, every material, and the alpha
// textures. Moving vertices leave it valid; a rebuild of the scene's geometry takes it again.
#pragma once

#include <vector>

#include "bounce/scene/scene.h"
#include "bounce/trace/cutout_view.h"

namespace bounce {

// Whether any triangle of the scene uses a material with cut-outs.
bool has_cutouts(const Scene& scene);

class Cutouts {
 public:
  void build(const Scene& scene);
  // Valid until the next build; empty (mesh_count 0) for a scene without cut-outs.
  CutoutView view() const;
  bool empty() const { return meshes_.empty(); }
  // Whether the copy still describes the scene's meshes (their counts unchanged).
  bool fits(const Scene& scene) const;

 private:
  std::vector<CutoutMesh> meshes_;
  std::vector<std::vector<vec2>> uvs_;
  std::vector<std::vector<uvec3>> triangles_;
  std::vector<std::vector<uint32_t>> materials_of_;
  std::vector<MaterialRecord> materials_;
  std::vector<std::vector<vec3>> texels_;
  std::vector<TextureView> textures_;
};

}  // namespace bounce
