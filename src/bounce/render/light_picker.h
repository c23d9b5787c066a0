// Choosing a light in proportion to its power: which light a path vertex samples (one per
// vertex, so many lights cost one shadow ray) and which light a photon path leaves. Built once
// per scene; the pick itself is a plain function over plain arrays.
#pragma once

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "bounce/core/cdf_sampling.h"
#include "bounce/core/device.h"
#include "bounce/scene/scene.h"

namespace bounce {

// The pick as plain data for kernels: the cdf and pmf arrays of a LightPicker.
struct LightPickerView {
  const float* cdf = nullptr;
  const float* pmf = nullptr;
  uint32_t count = 0;        // entries; 0 when nothing emits
  uint32_t light_count = 0;  // entries below this are Scene::lights, the rest area lights

  BOUNCE_HD bool empty() const { return count == 0; }
  // The entry that u in [0, 1) selects (core/cdf_sampling.h).
  BOUNCE_HD uint32_t pick(float u) const { return sample_cdf(cdf, count, u).entry; }
  // Stretches u, which picked `entry`, back over [0, 1): the rest of the sample stays
  // stratified when u is reused to place a point on the light.
  BOUNCE_HD float remap(uint32_t entry, float u) const { return cdf_stretch(cdf, entry, u); }
};
static_assert(std::is_trivially_copyable_v<LightPickerView>);

struct LightPicker {
  // Entries are Scene::lights (0 .. light_count - 1), then Scene::area_lights.
  uint32_t light_count = 0;
  std::vector<float> cdf;  // cumulative probability; empty when nothing emits
  std::vector<float> pmf;  // probability of each entry
  // Area light of each triangle by global id (Scene::triangle_offsets), -1 for non-emitters.
  std::vector<int32_t> area_light_of_triangle;
  bool has_sphere_lights = false;

  // `left_out`: Scene::lights indices picked never (weight 0), as the lights the direct pass
  // shades apart, so that no candidate is spent on them.
  static LightPicker build(const Scene& scene, std::span<const uint32_t> left_out = {});

  LightPickerView view() const {
    return {cdf.data(), pmf.data(), uint32_t(cdf.size()), light_count};
  }
  bool empty() const { return cdf.empty(); }
  // The entry that u in [0, 1) selects (binary search over the cdf).
  uint32_t pick(float u) const { return view().pick(u); }
  // Stretches u, which picked `entry`, back over [0, 1) (LightPickerView::remap).
  float remap(uint32_t entry, float u) const { return view().remap(entry, u); }
  float light_pmf(uint32_t light) const { return empty() ? 0.0f : pmf[light]; }
  float area_light_pmf(uint32_t area_light) const {
    return empty() ? 0.0f : pmf[light_count + area_light];
  }
};

}  // namespace bounce
