#include "bounce/scene/scene_edit.h"

#include <vector>

namespace bounce {

SceneChange move_area_light(Scene& scene, size_t index, vec3 offset) {
  const AreaLight& area = scene.area_lights.at(index);
  const uint32_t mesh_id = area.triangles.front().mesh;  // an area light lies in one mesh
  Mesh& mesh = scene.meshes[mesh_id];
  std::vector<uint8_t> move(mesh.positions.size(), 0);
  for (const TriangleRef& t : area.triangles) {
    const uvec3 v = mesh.triangles[t.triangle];
    move[v.x] = move[v.y] = move[v.z] = 1;
  }
  for (size_t i = 0; i < move.size(); ++i)
    if (move[i]) mesh.positions[i] += offset;
  for (AnimatedMesh& am : scene.animation.meshes)
    if (am.mesh == mesh_id)
      for (size_t i = 0; i < move.size(); ++i)
        if (move[i]) am.rest_positions[i] += offset;
  scene.derive();  // invalidates `area`
  return SceneChange{.moved_meshes = {mesh_id}, .lights = true};
}

}  // namespace bounce
