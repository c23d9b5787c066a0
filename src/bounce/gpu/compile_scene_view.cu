// nvcc check of the scene view and what reads it: surfaces at hits (render/surface.h), textures,
// lights and area lights (render/light_sampling.h), the light picker.
#include "bounce/render/light_picker.h"
#include "bounce/render/light_sampling.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene_view.h"

namespace bounce {

__global__ void check_scene_view(SceneView scene, LightPickerView picker, const Hit* hits,
                                 uint32_t n, vec3* out) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  vec3 sum(0.0f);
  if (hits[i].valid()) {
    const SurfaceHit s = surface_at(scene, hits[i], vec3(0.0f, 0.0f, 1.0f));
    sum += s.albedo + s.emission + s.normal;
    sum += vec3(float(scene.triangle_id(hits[i].mesh, hits[i].triangle)));
  }
  const vec2 u(float(i) / float(n), 0.5f);
  if (!picker.empty()) {
    const uint32_t entry = picker.pick(u.x);
    const float v = picker.remap(entry, u.x);
    if (entry < picker.light_count) {
      const LightRecord& light = scene.lights[entry];
      sum += light.power(scene.bounds.diagonal()) * spot_falloff(light, vec3(0.0f, -1.0f, 0.0f));
    } else {
      const AreaLightView& area = scene.area_lights[entry - picker.light_count];
      sum += sample_area_light_point(scene, area, vec2(v, u.y)).position + area.power();
    }
  }
  if (scene.texture_count > 0) sum += scene.textures[0].sample(u);
  out[i] = sum + scene.bounds.centre();
}

}  // namespace bounce
