#include "bounce/scene/scene_edit.h"

#include <vector>

namespace bounce {

namespace {

// Moves the vertices of mesh `mesh_id` marked in `move` (all when empty) and their rest copies.
SceneChange move_vertices(Scene& scene, uint32_t mesh_id, const std::vector<uint8_t>& move,
                          vec3 offset) {
  Mesh& mesh = scene.meshes.at(mesh_id);
  const auto shift = [&](std::vector<vec3>& positions) {
    for (size_t i = 0; i < positions.size(); ++i)
      if (move.empty() || move[i]) positions[i] += offset;
  };
  shift(mesh.positions);
  for (AnimatedMesh& am : scene.animation.meshes)
    if (am.mesh == mesh_id) shift(am.rest_positions);
  scene.derive();
  SceneChange change;
  change.moved_meshes = {mesh_id};
  change.lights = !scene.area_lights.empty();
  return change;
}

}  // namespace

SceneChange move_area_light(Scene& scene, size_t index, vec3 offset) {
  const AreaLight& area = scene.area_lights.at(index);
  const uint32_t mesh_id = area.triangles.front().mesh;  // an area light lies in one mesh
  const Mesh& mesh = scene.meshes[mesh_id];
  std::vector<uint8_t> move(mesh.positions.size(), 0);
  for (const TriangleRef& t : area.triangles) {
    const uvec3 v = mesh.triangles[t.triangle];
    move[v.x] = move[v.y] = move[v.z] = 1;
  }
  SceneChange change = move_vertices(scene, mesh_id, move, offset);
  change.lights = true;
  return change;
}

SceneChange move_mesh(Scene& scene, uint32_t index, vec3 offset) {
  return move_vertices(scene, index, {}, offset);
}

}  // namespace bounce
