#include "bounce/render/light_change_region.h"

#include <algorithm>
#include <utility>

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
  std::vector<uint32_t> moved;
  for (size_t k = 0; k < after.size(); ++k)
    if (before[k] != after[k] && is_punctual(after[k].type) && before[k].type == after[k].type)
      moved.push_back(uint32_t(k));
  if (moved.size() > size_t(LightsApart::kMax)) {
    // Spots last, then by power (a directional light's by its irradiance: the scene's size is
    // the same for all); ties by index, so the choice holds from frame to frame.
    const auto rank = [&](uint32_t k) {
      const LightRecord& l = after[k];
      const vec3 p = l.power(1.0f);
      return std::pair(l.type == LightType::kSpot, -(p.x + p.y + p.z));
    };
    std::stable_sort(moved.begin(), moved.end(),
                     [&](uint32_t a, uint32_t b) { return rank(a) < rank(b); });
    moved.resize(size_t(LightsApart::kMax));
    std::sort(moved.begin(), moved.end());
  }
  for (uint32_t k : moved) apart.index[apart.count++] = k;
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
