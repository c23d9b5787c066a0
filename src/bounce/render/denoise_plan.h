// What the CPU denoiser (denoiser.cpp) and the GPU's (gpu/device_denoiser.cu) decide the same
// way each frame: which a-trous passes run over which light, and the settings every pass shares.
// One copy, so the two backends cannot drift apart.
#pragma once

#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoiser.h"

namespace bounce::denoise {

struct AtrousPlan {
  int indirect_iterations = 0;  // passes over indirect light (0: none)
  bool half = false;            // indirect light filtered at half resolution
  // At full resolution with as many passes, both lights share each pass's geometry.
  bool both = false;
};

inline AtrousPlan atrous_plan(const DenoiseSettings& s, bool spatial, bool has_indirect,
                              int height) {
  AtrousPlan p;
  p.indirect_iterations =
      spatial && has_indirect ? indirect_iterations_for(s.indirect_iterations, height) : 0;
  p.half = p.indirect_iterations > 0 && s.indirect_resolution == 2;
  p.both = p.indirect_iterations > 0 && !p.half && p.indirect_iterations == s.atrous_iterations;
  return p;
}

// The first pass over direct (and indirect) light: inputs, the guide planes and the sigmas;
// the outputs are set per pass.
inline AtrousPass atrous_base(const DenoiseSettings& s, ConstSurfacePlanes surface,
                              const float* depth_slope, ConstRgbPlanes direct,
                              const float* direct_var, ConstRgbPlanes indirect,
                              const float* indirect_var, int width, int height) {
  AtrousPass base;
  base.surface = surface;
  base.depth_slope = depth_slope;
  base.direct = {direct, direct_var, {}, nullptr};
  base.indirect = {indirect, indirect_var, {}, nullptr};
  base.width = width;
  base.height = height;
  base.sigma_luminance = s.sigma_luminance;
  base.sigma_luminance_indirect = s.sigma_luminance_indirect;
  base.sigma_normal = s.sigma_normal;
  base.sigma_depth = s.sigma_depth;
  return base;
}

}  // namespace bounce::denoise
