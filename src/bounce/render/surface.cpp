#include "bounce/render/surface.h"

namespace bounce {

SurfaceHit surface_at(const Scene& scene, const Hit& hit, vec3 direction) {
  const Mesh& mesh = scene.meshes[hit.mesh];
  return surface_on(mesh.view(), scene.materials[mesh.materials[hit.triangle]], hit, direction,
                    scene.textures);
}

}  // namespace bounce
