// DeviceScene: the scene on the GPU. Copies of SceneData's flattened arrays (a SceneView whose
// pointers are device addresses), the light tables of direct light and photon emission, and our
// own BVH with the sphere lights (a TraceView whose triangle queries run on the device). Updated
// from the frame's SceneChange: nothing moves over the bus while the scene stands still.
#pragma once

#include <memory>

#include "bounce/gpu/device_buffer.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/photon_emission.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/bvh.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

class DeviceScene {
 public:
  // Catches up with `change` (everything on the first call).
  void update(const Scene& scene, const SceneData& data, const LightPicker& lights,
              const SceneChange& change);

  const SceneView& view() const { return view_; }
  const TraceView& trace() const { return trace_; }
  const LightPickerView& lights() const { return lights_view_; }
  const PhotonEmitterView& emitters() const { return emitters_view_; }
  vec3 emitted_power() const { return emitted_power_; }
  bool has_emitters() const { return !emitters_.empty(); }
  const Bvh& bvh() const { return bvh_; }
  size_t bytes() const;

 private:
  void upload_arrays(const SceneData& data);
  void upload_meshes(const SceneData& data);
  void upload_bvh();
  // A light table on the device (cdf and pmf).
  struct DeviceLightTable {
    DeviceBuffer<float> cdf, pmf;
    LightPickerView upload(const LightPicker& picker);
  };

  SceneView view_;
  TraceView trace_;
  LightPickerView lights_view_;
  PhotonEmitterView emitters_view_;
  PhotonEmitters emitters_;
  vec3 emitted_power_{0.0f};
  Bvh bvh_;
  bool built_ = false;
  bool moving_ = false;  // a mesh view on the device has a previous pose

  DeviceBuffer<MeshView> meshes_;
  DeviceBuffer<vec3> positions_, previous_positions_, normals_, texels_, area_normals_;
  DeviceBuffer<vec2> uvs_;
  DeviceBuffer<uvec3> triangles_;
  DeviceBuffer<uint32_t> triangle_materials_, triangle_offsets_;
  DeviceBuffer<MaterialRecord> materials_;
  DeviceBuffer<TextureView> textures_;
  DeviceBuffer<LightRecord> light_records_;
  DeviceBuffer<TriangleRef> area_triangles_;
  DeviceBuffer<float> area_cdf_;
  DeviceBuffer<AreaLightView> area_lights_;
  DeviceLightTable direct_lights_, emitter_lights_;
  DeviceBuffer<TraceSphere> spheres_;
  DeviceBuffer<BvhNode> bvh_nodes_;
  DeviceBuffer<BvhTriangle> bvh_triangles_;
  DeviceBuffer<BvhTriangleId> bvh_ids_;
};

}  // namespace bounce
