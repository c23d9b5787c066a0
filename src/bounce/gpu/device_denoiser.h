// The denoiser stage on the GPU: what Denoiser::run (render/denoiser.h) does, on device arrays,
// from the same per-pixel bodies (render/denoise_*.h), one thread per pixel where the CPU runs
// vectorised row loops. Debug views and raw copies are the CPU's only.
#pragma once

#include <cstdint>

#include "bounce/gpu/device_buffer.h"
#include "bounce/render/denoise_half.h"
#include "bounce/render/denoise_kernels.h"
#include "bounce/render/denoiser.h"
#include "bounce/render/gbuffer_view.h"

namespace bounce {

struct DeviceDenoiseFrame {
  ConstGBufferView g;  // device pointers, this frame's G-buffer with motion
  HistoryState state;
  IndirectHistory indirect_history;
  LightChangeRegion direct_region = LightChangeRegion::all();  // as DenoiseFrame's
};

class DeviceDenoiser {
 public:
  // Replaces direct (and indirect when not null) in place, as Denoiser::run does; both are
  // device arrays of g.width * g.height.
  void run(const DenoiseSettings& settings, const DeviceDenoiseFrame& frame, vec3* direct,
           vec3* indirect);

 private:
  // The CPU's Buffers as plain device planes (device_denoiser.cu documents them).
  struct Surface {
    DeviceBuffer<float> depth, nx, ny, nz;
    DeviceBuffer<uint32_t> object;
    void resize(size_t n);
    denoise::SurfacePlanes view();
  };
  struct Packed {  // denoise::PackedPlanes
    DeviceBuffer<uint32_t> w[denoise::PackedPlanes::kCount];
    void resize(size_t n);
    denoise::PackedPlanes view();
  };
  struct Rgb {
    DeviceBuffer<float> r, g, b;
    void resize(size_t n);
    denoise::RgbPlanes view();
  };
  struct History {  // denoise::HistoryPlanes
    DeviceBuffer<float> c[8];
    void resize(size_t n);
    void fill_zero();
    denoise::HistoryPlanes view();
  };
  void resize(int w, int h, bool keep_last);

  int width_ = 0, height_ = 0;
  bool valid_ = false, had_indirect_ = false, rest_valid_ = false;
  int rest_frames_ = 0;     // consecutive runs at rest (denoiser.cpp's Buffers::rest_frames)
  int history_frames_ = 0;  // frames since the last reset (Buffers::history_frames)
  Surface surface_, prev_surface_, half_surface_;
  Packed packed_, prev_packed_;  // kept and swapped with the surfaces
  History history_, prev_history_;
  DeviceBuffer<float> length_, prev_length_;
  // The modulation remodulation reads (at rest averaged in place; while reprojecting written from
  // last frame's: TemporalPass::prev_packed).
  Rgb rest_factor_, rest_emission_;
  DeviceBuffer<float> box_[5];
  DeviceBuffer<float> depth_slope_, var_direct_, var_indirect_;
  DeviceBuffer<uint32_t> row_short_;
  // a-trous ping-pong: direct rgb and variance, indirect rgb and variance
  Rgb filter_direct_[2], filter_indirect_[2];
  DeviceBuffer<float> filter_var_direct_[2], filter_var_indirect_[2];
  int half_width_ = 0, half_height_ = 0;
  DeviceBuffer<float> half_slope_;
  DeviceBuffer<float> half_moments_[5];  // the spatial variance at half resolution
  // Per light slot (denoise::HalfPlanes): the downsampled input, the ping-pong, the result.
  Rgb half_light_[3][denoise::kHalfMaxLights];
  DeviceBuffer<float> half_var_[3][denoise::kHalfMaxLights];
  Rgb upsampled_[denoise::kHalfMaxLights];
};

}  // namespace bounce
