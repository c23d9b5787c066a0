// The direct-light stage: light from every light source at each G-buffer pixel, with shadow
// rays; area lights (emissive triangles, spheres) take stratified QMC samples. The per-pixel
// body is direct_pixel (direct_kernel.h); this launcher traces its shadow rays in batches.
#pragma once

#include <cstdint>

#include "bounce/core/image.h"
#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// Writes emitted plus direct radiance towards `eye` for every pixel; returns shadow rays traced.
uint64_t compute_direct(const SceneView& scene, const Tracer& tracer, const GBuffer& g, vec3 eye,
                        const DirectSettings& settings, Image& out);

}  // namespace bounce
