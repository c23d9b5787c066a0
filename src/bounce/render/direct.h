// The direct-light stage: light from every light source at each G-buffer pixel, with shadow
// rays; area lights (emissive triangles, spheres) take stratified QMC samples. Scenes with more
// lights than DirectSettings::max_looped_lights take resampled light samples instead, and with
// DirectSettings::one_shadow_ray a pixel traces one ray for all its samples. The per-pixel body is
// direct_light_pixel (direct_kernel.h); this launcher traces its shadow rays in batches, and for
// the commonest scenes runs the light samples across rows of pixels (direct_takes_rows).
#pragma once

#include <cstdint>

#include "bounce/core/image.h"
#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// Writes emitted plus direct radiance towards `eye` for every pixel; returns shadow rays traced.
// `lights` picks lights by power for the resampled path (LightPicker::view()).
uint64_t compute_direct(const SceneView& scene, const LightPickerView& lights, const Tracer& tracer,
                        const GBuffer& g, vec3 eye, const DirectSettings& settings, Image& out);

// Whether compute_direct runs the light samples across rows of pixels as vector code
// (light_lane.h) rather than direct_light_pixel per pixel: every light is looped over (not
// resampled) and each is an area, point, spot or directional light. The frames are the same.
bool direct_takes_rows(const SceneView& scene, const LightPickerView& lights,
                       const DirectSettings& settings);

}  // namespace bounce
