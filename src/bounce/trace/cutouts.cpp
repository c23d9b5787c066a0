#include "bounce/trace/cutouts.h"

namespace bounce {

namespace {

bool mesh_has_cutouts(const Scene& scene, const Mesh& mesh) {
  for (const uint32_t m : mesh.materials)
    if (scene.materials[m].has_cutouts()) return true;
  return false;
}

}  // namespace

bool has_cutouts(const Scene& scene) {
  for (const Mesh& mesh : scene.meshes)
    if (mesh_has_cutouts(scene, mesh)) return true;
  return false;
}

void Cutouts::build(const Scene& scene) {
  *this = Cutouts{};
  if (!has_cutouts(scene)) return;
  const size_t n = scene.meshes.size();
  meshes_.resize(n);
  uvs_.resize(n);
  triangles_.resize(n);
  materials_of_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Mesh& mesh = scene.meshes[i];
    if (!mesh_has_cutouts(scene, mesh)) continue;
    uvs_[i] = mesh.uvs;
    triangles_[i] = mesh.triangles;
    materials_of_[i] = mesh.materials;
    meshes_[i] = {uvs_[i].empty() ? nullptr : uvs_[i].data(), triangles_[i].data(),
                  materials_of_[i].data()};
  }
  materials_.assign(scene.materials.begin(), scene.materials.end());
  texels_.resize(scene.textures.size());
  textures_.resize(scene.textures.size());
  for (const MaterialRecord& m : materials_) {
    const int t = m.alpha_texture;
    if (!m.has_cutouts() || t < 0 || !texels_[size_t(t)].empty()) continue;
    const Texture& texture = scene.textures[size_t(t)];
    texels_[size_t(t)] = texture.texels;
    textures_[size_t(t)] = {texels_[size_t(t)].data(), texture.width, texture.height};
  }
}

bool Cutouts::fits(const Scene& scene) const {
  if (meshes_.empty()) return true;  // moving vertices brings no cut-outs in
  if (scene.meshes.size() != meshes_.size()) return false;
  for (size_t i = 0; i < meshes_.size(); ++i)
    if (meshes_[i].triangles && (scene.meshes[i].triangles.size() != triangles_[i].size() ||
                                 scene.meshes[i].uvs.size() != uvs_[i].size()))
      return false;
  return true;
}

CutoutView Cutouts::view() const {
  if (meshes_.empty()) return {};
  return {meshes_.data(), uint32_t(meshes_.size()), materials_.data(), textures_.data()};
}

}  // namespace bounce
