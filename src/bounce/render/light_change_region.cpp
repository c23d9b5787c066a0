#include "bounce/render/light_change_region.h"

namespace bounce {

LightChangeRegion light_change_region(std::span<const LightRecord> before,
                                      std::span<const LightRecord> after) {
  if (before.size() != after.size()) return LightChangeRegion::all();
  LightChangeRegion r = LightChangeRegion::none();
  for (size_t k = 0; k < before.size(); ++k) {
    const LightRecord &a = before[k], &b = after[k];
    if (a == b) continue;
    if (a.type != LightType::kSpot || b.type != LightType::kSpot ||
        r.cones + 2 > LightChangeRegion::kMaxCones)
      return LightChangeRegion::all();
    for (const LightRecord* l : {&a, &b}) {
      if (!(max_component(l->intensity) > 0.0f)) continue;  // it sent no light
      r.apex[r.cones] = l->position;
      r.axis[r.cones] = glm::normalize(l->direction);
      r.cos_outer[r.cones] = l->cos_outer;
      ++r.cones;
    }
  }
  return r;
}

LightsApart moved_punctual_lights(std::span<const LightRecord> before,
                                  std::span<const LightRecord> after) {
  LightsApart apart;
  if (before.size() != after.size()) return apart;
  for (size_t k = 0; k < after.size(); ++k) {
    if (before[k] == after[k] || !is_punctual(after[k].type) || before[k].type != after[k].type)
      continue;
    if (apart.count == LightsApart::kMax) return LightsApart{};
    apart.index[apart.count++] = uint32_t(k);
  }
  return apart;
}

std::vector<LightRecord> lights_in_history(std::span<const LightRecord> lights,
                                           const LightsApart& apart) {
  std::vector<LightRecord> out(lights.begin(), lights.end());
  for (int k = 0; k < apart.count; ++k) {
    LightRecord dark;
    dark.type = out[apart.index[k]].type;
    out[apart.index[k]] = dark;
  }
  return out;
}

LightChangeRegion light_change_region(const SceneChange& change,
                                      std::span<const LightRecord> before,
                                      std::span<const LightRecord> after) {
  const bool lights_only = change.lights && !change.everything && !change.geometry() &&
                           !change.materials && !change.parameters;
  return lights_only ? light_change_region(before, after) : LightChangeRegion::all();
}

}  // namespace bounce
