// Alpha cut-outs as ray queries see them: which triangle hits are holes that every ray (primary,
// shadow, photon) passes through. Plain data and one test, shared by Embree's intersection filter
// and our BVH's traversal (bvh_traversal.h), host and device alike. Cutouts (cutouts.h) owns the
// arrays on the host.
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/scene/material.h"
#include "bounce/scene/material_eval.h"
#include "bounce/scene/texture.h"

namespace bounce {

// One mesh's arrays the test reads; triangles is null for a mesh without cut-out materials.
struct CutoutMesh {
  const vec2* uvs = nullptr;  // per vertex, or null (the material's alpha factor alone)
  const uvec3* triangles = nullptr;
  const uint32_t* materials = nullptr;  // per triangle
};

struct CutoutView {
  const CutoutMesh* meshes = nullptr;  // per scene mesh
  uint32_t mesh_count = 0;             // 0: no cut-outs anywhere
  const MaterialRecord* materials = nullptr;
  const TextureView* textures = nullptr;  // the alpha textures (others left empty)

  // Whether the hit on `triangle` of `mesh` at barycentric (u, v) (the weights of vertices 1 and
  // 2) falls in a hole.
  BOUNCE_HD bool passes(uint32_t mesh, uint32_t triangle, float u, float v) const {
    if (mesh >= mesh_count) return false;
    const CutoutMesh& m = meshes[mesh];
    if (!m.triangles) return false;
    const MaterialRecord& material = materials[m.materials[triangle]];
    if (!material.has_cutouts()) return false;
    vec2 uv(0.0f);
    if (m.uvs) {
      const uvec3 t = m.triangles[triangle];
      uv = (1.0f - u - v) * m.uvs[t.x] + u * m.uvs[t.y] + v * m.uvs[t.z];
    }
    return cut_away(material, textures, uv);
  }
};
static_assert(std::is_trivially_copyable_v<CutoutView>);

}  // namespace bounce
