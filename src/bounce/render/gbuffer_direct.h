// The G-buffer and direct light in one parallel pass over bands of the frame: each band's
// direct light runs right after its G-buffer, on the same core, and reads the G-buffer's
// 104 bytes a pixel from that core's cache instead of from memory (at 1280 x 720 the G-buffer is
// 96 MB, three times the last-level cache). The frames are those of build_gbuffer followed by
// compute_direct.
#pragma once

#include <cstdint>
#include <functional>

#include "bounce/core/image.h"
#include "bounce/render/direct.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/light_picker.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct GBufferAndDirect {
  uint64_t primary_rays = 0;
  uint64_t shadow_rays = 0;
  // The pass's wall time shared between the two by the time the threads spent in each.
  double gbuffer_ms = 0.0;
  double direct_ms = 0.0;
  double band_ms = 0.0;  // after_band's
};

// Called with each band (x0, y0, x1, y1) after its G-buffer and direct light, on the same
// thread (Technique::gbuffer_band).
using AfterBand = std::function<void(int, int, int, int)>;

// build_gbuffer (all but the motion: compute_motion; with `raster` as build_gbuffer takes it) and
// compute_direct, band by band, then after_band (if any) on the band. `g`, `direct` and `apart`
// (compute_direct's; null without lights set apart) are already sized.
GBufferAndDirect build_gbuffer_and_direct(const SceneView& scene, const LightPickerView& lights,
                                          const Tracer& tracer, const CameraRays& camera,
                                          vec2 subpixel, const DirectSettings& settings, GBuffer& g,
                                          Image& direct, Image* apart,
                                          const AfterBand& after_band = {},
                                          const PrimaryRaster* raster = nullptr);

}  // namespace bounce
