#include "bounce/gpu/device_scene.h"

#include <vector>

#include "bounce/trace/tracer.h"

namespace bounce {

LightPickerView DeviceScene::DeviceLightTable::upload(const LightPicker& picker) {
  cdf.upload(picker.cdf);
  pmf.upload(picker.pmf);
  LightPickerView v = picker.view();
  v.cdf = cdf.data();
  v.pmf = pmf.data();
  return v;
}

// The views inside the arrays point at host memory: point them at the device copies.
void DeviceScene::upload_meshes(const SceneData& data) {
  const SceneData::Arrays a = data.arrays();
  std::vector<MeshView> meshes(a.meshes.begin(), a.meshes.end());
  moving_ = false;
  for (MeshView& m : meshes) {
    m.positions = relocate(m.positions, a.positions, positions_);
    m.previous_positions =
        relocate(m.previous_positions, a.previous_positions, previous_positions_);
    m.normals = relocate(m.normals, a.normals, normals_);
    m.uvs = relocate(m.uvs, a.uvs, uvs_);
    m.triangles = relocate(m.triangles, a.triangles, triangles_);
    moving_ |= m.previous_positions != nullptr;
    m.materials = relocate(m.materials, a.triangle_materials, triangle_materials_);
    m.face_normals = nullptr;  // a GPU computes each from the corners it loads anyway
  }
  meshes_.upload(meshes);
  view_.meshes = meshes_.data();
}

void DeviceScene::upload_arrays(const SceneData& data) {
  const SceneData::Arrays a = data.arrays();
  positions_.upload(a.positions);
  previous_positions_.upload(a.previous_positions);
  normals_.upload(a.normals);
  uvs_.upload(a.uvs);
  triangles_.upload(a.triangles);
  triangle_materials_.upload(a.triangle_materials);
  triangle_offsets_.upload(a.triangle_offsets);
  materials_.upload(a.materials);
  texels_.upload(a.texels);
  light_records_.upload(a.lights);
  area_triangles_.upload(a.area_triangles);
  area_normals_.upload(a.area_normals);
  area_cdf_.upload(a.area_cdf);
  upload_meshes(data);
  std::vector<TextureView> textures(a.textures.begin(), a.textures.end());
  for (TextureView& t : textures) t.texels = relocate(t.texels, a.texels, texels_);
  textures_.upload(textures);
  std::vector<AreaLightView> areas(a.area_lights.begin(), a.area_lights.end());
  for (AreaLightView& l : areas) {
    l.triangles = relocate(l.triangles, a.area_triangles, area_triangles_);
    l.normals = relocate(l.normals, a.area_normals, area_normals_);
    l.cdf = relocate(l.cdf, a.area_cdf, area_cdf_);
  }
  area_lights_.upload(areas);

  view_ = data.view();
  view_.meshes = meshes_.data();
  view_.triangle_offsets = triangle_offsets_.data();
  view_.materials = materials_.data();
  view_.textures = textures_.data();
  view_.lights = light_records_.data();
  view_.area_lights = area_lights_.data();
}

void DeviceScene::upload_bvh() {
  bvh_nodes_.upload(bvh_.nodes());
  bvh_triangles_.upload(bvh_.triangles());
  bvh_ids_.upload(bvh_.ids());
  trace_.triangles = nullptr;  // no Embree on the device: the BVH answers
  trace_.bvh = bvh_.view();
  trace_.bvh.nodes = bvh_nodes_.data();
  trace_.bvh.triangles = bvh_triangles_.data();
  trace_.bvh.ids = bvh_ids_.data();
}

void DeviceScene::update(const Scene& scene, const SceneData& data, const LightPicker& lights,
                         const SceneChange& change) {
  const bool everything = !built_ || change.everything;
  if (everything) {
    bvh_.build(scene);
  } else if (!change.moved_meshes.empty()) {
    bvh_.refit(scene, change.moved_meshes);
  }
  if (everything || change.geometry()) upload_bvh();
  if (everything || change.geometry() || change.lights || change.materials)
    upload_arrays(data);
  else if (moving_)
    upload_meshes(data);  // meshes that moved last frame stand still now (no previous pose)
  if (everything || change.geometry() || change.lights || change.materials) {
    lights_view_ = direct_lights_.upload(lights);
    emitters_ = PhotonEmitters::from(scene);
    emitted_power_ = emitters_.total_power;
    emitters_view_ = emitters_.view();
    emitters_view_.picker = emitter_lights_.upload(emitters_.picker);
    const std::vector<TraceSphere> spheres = trace_spheres(scene);
    spheres_.upload(spheres);
    trace_.spheres = spheres_.data();
    trace_.sphere_count = uint32_t(spheres.size());
  }
  built_ = true;
}

size_t DeviceScene::bytes() const {
  return meshes_.bytes() + positions_.bytes() + previous_positions_.bytes() + normals_.bytes() +
         texels_.bytes() + area_normals_.bytes() + uvs_.bytes() + triangles_.bytes() +
         triangle_materials_.bytes() + triangle_offsets_.bytes() + materials_.bytes() +
         textures_.bytes() + light_records_.bytes() + area_triangles_.bytes() + area_cdf_.bytes() +
         area_lights_.bytes() + spheres_.bytes() + bvh_nodes_.bytes() + bvh_triangles_.bytes() +
         bvh_ids_.bytes();
}

}  // namespace bounce
