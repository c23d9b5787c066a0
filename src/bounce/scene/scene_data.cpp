#include "bounce/scene/scene_data.h"

#include <algorithm>

namespace bounce {

SceneData SceneData::from(const Scene& scene) {
  SceneData data;
  data.build(scene);
  return data;
}

void SceneData::build(const Scene& scene) {
  const size_t mesh_count = scene.meshes.size();
  ranges_.resize(mesh_count);
  size_t vertices = 0, normals = 0, uvs = 0, triangles = 0;
  for (size_t m = 0; m < mesh_count; ++m) {
    const Mesh& mesh = scene.meshes[m];
    MeshRange& r = ranges_[m];
    r.first_vertex = vertices;
    r.first_normal = normals;
    r.first_uv = uvs;
    r.first_triangle = triangles;
    r.vertex_count = uint32_t(mesh.positions.size());
    r.triangle_count = uint32_t(mesh.triangles.size());
    r.normals = !mesh.normals.empty();
    r.uvs = !mesh.uvs.empty();
    vertices += mesh.positions.size();
    normals += mesh.normals.size();
    uvs += mesh.uvs.size();
    triangles += mesh.triangles.size();
  }
  positions_.resize(vertices);
  previous_positions_.resize(vertices);
  moved_.assign(mesh_count, 0);
  normals_.resize(normals);
  uvs_.resize(uvs);
  triangles_.resize(triangles);
  face_normals_.resize(triangles);
  triangle_materials_.resize(triangles);
  for (uint32_t m = 0; m < mesh_count; ++m) {
    const Mesh& mesh = scene.meshes[m];
    const MeshRange& r = ranges_[m];
    copy_vertices(scene, m);
    std::copy(mesh.uvs.begin(), mesh.uvs.end(), uvs_.begin() + r.first_uv);
    std::copy(mesh.triangles.begin(), mesh.triangles.end(), triangles_.begin() + r.first_triangle);
    std::copy(mesh.materials.begin(), mesh.materials.end(),
              triangle_materials_.begin() + r.first_triangle);
  }
  triangle_offsets_ = scene.triangle_offsets;

  // Each texture's whole chain of levels (a third more texels), for lookups whose footprint
  // covers many texels (the G-buffer's).
  size_t texels = 0;
  for (const Texture& t : scene.textures) texels += texture_chain_texels(t.width, t.height);
  texels_.resize(texels);
  textures_.resize(scene.textures.size());
  texels = 0;
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const Texture& t = scene.textures[i];
    std::copy(t.texels.begin(), t.texels.end(), texels_.begin() + texels);
    textures_[i] = {texels_.data() + texels, t.width, t.height, mean_texel(t)};
    build_texture_levels(textures_[i], texels_.data() + texels);
    texels += texture_chain_texels(t.width, t.height);
  }
  copy_small_arrays(scene);
  point_meshes();
}

void SceneData::refresh(const Scene& scene, std::span<const uint32_t> moved_meshes) {
  if (!same_layout(scene)) {
    build(scene);
    return;
  }
  std::fill(moved_.begin(), moved_.end(), 0);
  for (uint32_t m : moved_meshes) {
    const MeshRange& r = ranges_[m];
    std::copy_n(positions_.begin() + r.first_vertex, r.vertex_count,
                previous_positions_.begin() + r.first_vertex);
    moved_[m] = 1;
    copy_vertices(scene, m);
  }
  copy_small_arrays(scene);
  point_meshes();
}

void SceneData::forget_motion() {
  if (std::find(moved_.begin(), moved_.end(), 1) == moved_.end()) return;
  std::fill(moved_.begin(), moved_.end(), 0);
  point_meshes();
}

bool SceneData::same_layout(const Scene& scene) const {
  if (scene.meshes.size() != ranges_.size() || scene.textures.size() != textures_.size())
    return false;
  for (size_t m = 0; m < ranges_.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const MeshRange& r = ranges_[m];
    if (mesh.positions.size() != r.vertex_count || mesh.triangles.size() != r.triangle_count ||
        mesh.normals.empty() == r.normals || mesh.uvs.empty() == r.uvs)
      return false;
  }
  return true;
}

void SceneData::copy_vertices(const Scene& scene, uint32_t m) {
  const Mesh& mesh = scene.meshes[m];
  const MeshRange& r = ranges_[m];
  std::copy(mesh.positions.begin(), mesh.positions.end(), positions_.begin() + r.first_vertex);
  std::copy(mesh.normals.begin(), mesh.normals.end(), normals_.begin() + r.first_normal);
  vec3* face = face_normals_.data() + r.first_triangle;
  for (const uvec3& t : mesh.triangles)
    *face++ = triangle_unit_normal(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]);
}

void SceneData::copy_small_arrays(const Scene& scene) {
  materials_.assign(scene.materials.begin(), scene.materials.end());
  lights_.assign(scene.lights.begin(), scene.lights.end());
  bounds_ = scene.bounds;
  // Maps are immutable: sharing the scene's keeps the view's pointers valid without a copy.
  environment_map_ = scene.environment_map;
  environment_ = -1;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type == LightType::kEnvironment) environment_ = int32_t(i);

  size_t triangles = 0;
  for (const AreaLight& a : scene.area_lights) triangles += a.triangles.size();
  area_triangles_.clear();
  area_normals_.clear();
  area_cdf_.clear();
  area_triangles_.reserve(triangles);
  area_normals_.reserve(triangles);
  area_cdf_.reserve(triangles);
  area_lights_.resize(scene.area_lights.size());
  for (size_t i = 0; i < scene.area_lights.size(); ++i) {
    const AreaLight& a = scene.area_lights[i];
    const size_t first = area_triangles_.size();
    area_triangles_.insert(area_triangles_.end(), a.triangles.begin(), a.triangles.end());
    area_normals_.insert(area_normals_.end(), a.normals.begin(), a.normals.end());
    area_cdf_.insert(area_cdf_.end(), a.cdf.begin(), a.cdf.end());
    area_lights_[i] = {a.radiance,
                       a.area,
                       area_triangles_.data() + first,
                       area_normals_.data() + first,
                       area_cdf_.data() + first,
                       uint32_t(a.triangles.size())};
  }
}

void SceneData::point_meshes() {
  meshes_.resize(ranges_.size());
  for (size_t m = 0; m < ranges_.size(); ++m) {
    const MeshRange& r = ranges_[m];
    meshes_[m] = {positions_.data() + r.first_vertex,
                  r.normals ? normals_.data() + r.first_normal : nullptr,
                  r.uvs ? uvs_.data() + r.first_uv : nullptr,
                  triangles_.data() + r.first_triangle,
                  triangle_materials_.data() + r.first_triangle,
                  r.vertex_count,
                  r.triangle_count,
                  moved_[m] ? previous_positions_.data() + r.first_vertex : nullptr,
                  face_normals_.data() + r.first_triangle};
  }
}

SceneView SceneData::view() const {
  SceneView v;
  v.meshes = meshes_.data();
  v.mesh_count = uint32_t(meshes_.size());
  v.triangle_offsets = triangle_offsets_.data();
  v.materials = materials_.data();
  v.material_count = uint32_t(materials_.size());
  v.textures = textures_.data();
  v.texture_count = uint32_t(textures_.size());
  v.lights = lights_.data();
  v.light_count = uint32_t(lights_.size());
  v.area_lights = area_lights_.data();
  v.area_light_count = uint32_t(area_lights_.size());
  v.bounds = bounds_;
  v.environment = environment_;
  if (environment_ >= 0 && environment_map_) v.environment_map = environment_map_->view();
  return v;
}

}  // namespace bounce
