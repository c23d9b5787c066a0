// The direct-light stage: light from every light source at each G-buffer pixel, with shadow
// rays; area lights (emissive triangles, spheres) take stratified QMC samples. Scenes with more
// lights than DirectSettings::max_looped_lights take resampled light samples instead, and with
// DirectSettings::one_shadow_ray a pixel traces one ray for all its samples. The per-pixel body is
// direct_light_pixel (direct_kernel.h); this launcher traces its shadow rays in batches, and for
// the commonest scenes runs the light samples across rows of pixels (direct_takes_rows).
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// Writes emitted plus direct radiance towards `eye` for every pixel; returns shadow rays traced.
// `lights` picks lights by power for the resampled path (LightPicker::view()). The light of the
// lights set apart (DirectSettings::apart) goes to `apart` (sized as `out`; needed when any is).
uint64_t compute_direct(const SceneView& scene, const LightPickerView& lights, const Tracer& tracer,
                        const GBuffer& g, vec3 eye, const DirectSettings& settings, Image& out,
                        Image* apart = nullptr);

struct ShadowBatch;  // direct.cpp: shadow rays traced a batch at a time

// compute_direct for one frame, a block of pixels at a time: compute_direct runs its tiles in
// parallel; the renderer runs each band of rows right after that band's G-buffer
// (build_gbuffer_and_direct). Blocks of different threads must not overlap.
class DirectPass {
 public:
  DirectPass(const SceneView& scene, const LightPickerView& lights, const Tracer& tracer,
             const GBuffer& g, vec3 eye, const DirectSettings& settings, Image& out,
             Image* apart = nullptr);
  ~DirectPass();
  DirectPass(const DirectPass&) = delete;
  DirectPass& operator=(const DirectPass&) = delete;

  // The side of the square tiles the pass works in (32 for the row loop, else 8).
  int tile() const;
  // The pixels of [x0, x1) x [y0, y1), tile by tile, on the calling thread; final when it
  // returns. A pixel's light does not depend on the block or the tiles: its samples and shadow
  // rays are its own, and their light reaches it in the order the rays were made.
  void run(int x0, int y0, int x1, int y1);
  uint64_t shadow_rays() const;  // traced so far, by every thread

 private:
  void row_tile(int x0, int y0, int x1, int y1);
  void pixel_tile(int x0, int y0, int x1, int y1);

  SceneView scene_;  // plain views, copied: the caller may pass temporaries
  LightPickerView lights_;
  const Tracer& tracer_;
  ConstGBufferView view_;
  vec3 eye_;
  DirectSettings settings_;
  vec3* pixels_;
  vec3* apart_pixels_;   // null without lights set apart
  bool rows_;            // direct_takes_rows
  bool select_ = false;  // one shadow ray a pixel among several samples
  std::vector<PunctualLane> punctual_;
  std::vector<PunctualLane> apart_;          // the lights set apart (DirectSettings::apart)
  std::vector<std::vector<float>> corners_;  // each area light's (area_light_corners)
  std::unique_ptr<tbb::enumerable_thread_specific<ShadowBatch>> batches_;
};

// Whether compute_direct runs the light samples across rows of pixels as vector code
// (light_lane.h) rather than direct_light_pixel per pixel: every light is looped over (not
// resampled) and each is an area, point, spot or directional light. The frames are the same.
bool direct_takes_rows(const SceneView& scene, const LightPickerView& lights,
                       const DirectSettings& settings);

}  // namespace bounce
