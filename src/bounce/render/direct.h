// The direct-light stage: light from every light source at each G-buffer pixel, with shadow
// rays; area lights (emissive triangles, spheres) take stratified QMC samples.
#pragma once

#include <cstdint>

#include "bounce/core/image.h"
#include "bounce/render/gbuffer.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct DirectSettings {
  int light_samples = 16;  // per area or sphere light, per pixel
  uint32_t frame = 0;      // rotates the sample pattern from frame to frame
  uint32_t seed = 0;
};

// Writes emitted plus direct radiance towards `eye` for every pixel; returns shadow rays traced.
uint64_t compute_direct(const Scene& scene, const Tracer& tracer, const GBuffer& g, vec3 eye,
                        const DirectSettings& settings, Image& out);

// A per-pixel, per-light rotation of the sample pattern (Cranley-Patterson), as two floats.
vec2 pattern_offset(uint32_t pixel, uint32_t light, uint32_t frame, uint32_t seed);

}  // namespace bounce
