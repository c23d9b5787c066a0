#include "bounce/render/light_picker.h"

namespace bounce {

namespace {

// A light's weight for picking: its power averaged over the channels.
float pick_weight(vec3 power) {
  const float w = (power.x + power.y + power.z) / 3.0f;
  return w > 0.0f && std::isfinite(w) ? w : 0.0f;
}

}  // namespace

LightPicker LightPicker::build(const Scene& scene, std::span<const uint32_t> left_out) {
  LightPicker p;
  p.light_count = uint32_t(scene.lights.size());
  const float scene_radius = 0.5f * scene.bounds.diagonal();
  std::vector<double> weights;
  for (const Light& l : scene.lights) {
    weights.push_back(pick_weight(l.power(scene_radius)));
    if (l.type == LightType::kSphere) p.has_sphere_lights = true;
  }
  for (uint32_t l : left_out)
    if (l < p.light_count) weights[l] = 0.0;
  for (const AreaLight& a : scene.area_lights) weights.push_back(pick_weight(a.power()));
  double total = 0.0;
  for (double w : weights) total += w;
  if (total > 0.0) {
    double running = 0.0;
    for (double w : weights) {
      running += w;
      p.pmf.push_back(float(w / total));
      p.cdf.push_back(float(running / total));
    }
    // From the last light with power on, the cdf is exactly 1, so that rounding never lets
    // u < 1 land on a powerless entry.
    size_t last = weights.size() - 1;
    while (weights[last] <= 0.0) --last;
    for (size_t i = last; i < p.cdf.size(); ++i) p.cdf[i] = 1.0f;
  }

  p.area_light_of_triangle.assign(scene.triangle_count(), -1);
  for (size_t a = 0; a < scene.area_lights.size(); ++a)
    for (const TriangleRef& t : scene.area_lights[a].triangles)
      p.area_light_of_triangle[scene.triangle_offsets[t.mesh] + t.triangle] = int32_t(a);
  return p;
}

}  // namespace bounce
