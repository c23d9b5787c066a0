// DeviceDenoiser (device_denoiser.h): Denoiser::run's passes in the same order, each pass a
// launch of the CPU's per-pixel body (the *_pixel entry points of render/denoise_*.h). Planes
// have no padding here: the GPU bodies clamp their taps.
#include "bounce/gpu/device_denoiser.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "bounce/gpu/launch.h"
#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoise_half.h"
#include "bounce/render/denoise_plan.h"
#include "bounce/render/denoise_temporal.h"
#include "bounce/render/denoise_variance.h"

namespace bounce {

// Launchers, outside the class: device lambdas may not sit in private members.
namespace device_denoise {

template <bool kIndirect, bool kRest>
void temporal(const denoise::TemporalPass& pass, uint32_t* row_short) {
  const denoise::TemporalPass p = pass;
  launch_2d(p.width, p.height, [=] __device__(int x, int y) {
    // Every writer stores the same 1: the race is harmless.
    if (denoise::temporal_pixel<kIndirect, kRest>(p, x, y)) row_short[y] = 1u;
  });
}

void depth_slope(const float* depth, int w, int h, float* slope) {
  launch_2d(w, h, [=] __device__(int x, int y) {
    const size_t row = size_t(y) * size_t(w);
    const size_t up = y > 0 ? row - size_t(w) : row, down = y + 1 < h ? row + size_t(w) : row;
    slope[row + size_t(x)] = denoise::depth_slope_pixel<true>(depth, w, row, up, down, x);
  });
}

// The box sums on rows within the box of a short row, then the spatial estimate on short rows
// (the rows the CPU computes; the others are not read).
void spatial_variance(const denoise::BoxPass& box, const denoise::VariancePass& variance,
                      const uint32_t* row_short) {
  const denoise::BoxPass b = box;
  const denoise::VariancePass v = variance;
  const int h = v.height;
  launch_2d(v.width, h, [=] __device__(int x, int y) {
    bool needed = false;
    const int y0 = y - denoise::kVarianceBox > 0 ? y - denoise::kVarianceBox : 0;
    const int y1 = y + denoise::kVarianceBox < h - 1 ? y + denoise::kVarianceBox : h - 1;
    for (int k = y0; k <= y1; ++k) needed |= row_short[k] != 0;
    if (needed) denoise::box_row_pixel(b, size_t(y) * size_t(b.width), x);
  });
  launch_2d(v.width, h, [=] __device__(int x, int y) {
    if (row_short[y] != 0) denoise::spatial_variance_pixel(v, x, y);
  });
}

template <bool kIndirect, bool kVariance, bool kLuminanceDirect, bool kLuminanceIndirect>
void atrous(const denoise::AtrousPass& pass) {
  const denoise::AtrousPass p = pass;
  launch_2d(p.width, p.height, [=] __device__(int x, int y) {
    denoise::atrous_pixel<1, kIndirect, kVariance, kLuminanceDirect, kLuminanceIndirect>(p, x, y);
  });
}

void atrous(const denoise::AtrousPass& pass, bool both, bool variance) {
  denoise::dispatch_atrous(
      pass, both, variance, [&]<bool... kSwitches>() { atrous<kSwitches...>(pass); });
}

void downsample(const denoise::HalfDownsample& pass, int half_height) {
  const denoise::HalfDownsample p = pass;
  launch_2d(p.half_width, half_height,
            [=] __device__(int x, int y) { denoise::downsample_pixel(p, x, y); });
}

void half_variance(const denoise::HalfVariancePass& pass) {
  const denoise::HalfVariancePass p = pass;
  launch_2d(p.width, p.height,
            [=] __device__(int x, int y) { denoise::half_variance_pixel(p, x, y); });
}

void upsample(const denoise::HalfUpsample& pass) {
  const denoise::HalfUpsample p = pass;
  launch_2d(p.width, p.height, [=] __device__(int x, int y) { denoise::upsample_pixel(p, x, y); });
}

// The device's passes for the schedules both backends share (denoise_plan.h).
struct DevicePasses {
  void atrous(const denoise::AtrousPass& pass, bool both, bool variance) const {
    device_denoise::atrous(pass, both, variance);
  }
  void depth_slope(const float* depth, int w, int h, float* slope) const {
    device_denoise::depth_slope(depth, w, h, slope);
  }
  void downsample(const denoise::HalfDownsample& pass, int half_height) const {
    device_denoise::downsample(pass, half_height);
  }
  void half_variance(const denoise::HalfVariancePass& pass) const {
    device_denoise::half_variance(pass);
  }
  void upsample(const denoise::HalfUpsample& pass) const { device_denoise::upsample(pass); }
};

template <bool kIndirect, bool kRest>
void remodulate(const denoise::RemodulatePass& pass, size_t n) {
  const denoise::RemodulatePass p = pass;
  launch(n, [=] __device__(uint32_t i) { denoise::remodulate_pixel<kIndirect, kRest>(p, i); });
}

}  // namespace device_denoise

void DeviceDenoiser::Surface::resize(size_t n) {
  for (auto* b : {&depth, &nx, &ny, &nz}) {
    b->resize(n);
    b->fill_zero();
  }
  object.resize(n);
  if (n) BOUNCE_CUDA(cudaMemset(object.data(), 0xFF, n * sizeof(uint32_t)));  // kNoPrimitive
}

denoise::SurfacePlanes DeviceDenoiser::Surface::view() {
  return {depth.data(), nx.data(), ny.data(), nz.data(), object.data()};
}

void DeviceDenoiser::Packed::resize(size_t n) {
  for (auto& p : w) {
    p.resize(n);
    p.fill_zero();
  }
}

denoise::PackedPlanes DeviceDenoiser::Packed::view() {
  denoise::PackedPlanes p;
  for (int k = 0; k < denoise::PackedPlanes::kCount; ++k) p.w[k] = w[k].data();
  return p;
}

void DeviceDenoiser::Rgb::resize(size_t n) {
  for (auto* b : {&r, &g, &b}) {
    b->resize(n);
    b->fill_zero();
  }
}

denoise::RgbPlanes DeviceDenoiser::Rgb::view() {
  return {r.data(), g.data(), b.data()};
}

void DeviceDenoiser::History::resize(size_t n) {
  for (auto& p : c) p.resize(n);
}

void DeviceDenoiser::History::fill_zero() {
  for (auto& p : c) p.fill_zero();
}

denoise::HistoryPlanes DeviceDenoiser::History::view() {
  denoise::HistoryPlanes h;
  for (int k = 0; k < 8; ++k) h.c[k] = c[k].data();
  return h;
}

// As Denoiser's Buffers::resize: with keep_last the last run's surfaces, history and lengths
// keep their old size, to be reprojected across the size change.
void DeviceDenoiser::resize(int w, int h, bool keep_last) {
  width_ = w;
  height_ = h;
  const size_t n = size_t(w) * size_t(h);
  if (!keep_last) {
    surface_.resize(n);
    packed_.resize(n);
    history_.resize(n);
    history_.fill_zero();
    length_.resize(n);
    length_.fill_zero();
  }
  prev_surface_.resize(n);
  prev_packed_.resize(n);
  prev_history_.resize(n);
  prev_history_.fill_zero();
  prev_length_.resize(n);
  prev_length_.fill_zero();
  for (Rgb* p : {&rest_factor_, &rest_emission_, &upsampled_[0], &upsampled_[1], &filter_direct_[0],
                 &filter_direct_[1], &filter_indirect_[0], &filter_indirect_[1]})
    p->resize(n);
  for (auto* b : {&box_[0], &box_[1], &box_[2], &box_[3], &box_[4], &depth_slope_, &var_direct_,
                  &var_indirect_, &filter_var_direct_[0], &filter_var_direct_[1],
                  &filter_var_indirect_[0], &filter_var_indirect_[1]}) {
    b->resize(n);
    b->fill_zero();
  }
  row_short_.resize(size_t(h));
  half_width_ = (w + 1) / 2;
  half_height_ = (h + 1) / 2;
  const size_t half_n = size_t(half_width_) * size_t(half_height_);
  half_surface_.resize(half_n);
  half_slope_.resize(half_n);
  for (auto& m : half_moments_) m.resize(half_n);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < denoise::kHalfMaxLights; ++l) {
      half_light_[k][l].resize(half_n);
      half_var_[k][l].resize(half_n);
      half_var_[k][l].fill_zero();
    }
  valid_ = valid_ && keep_last;
}

void DeviceDenoiser::run(const DenoiseSettings& settings, const DeviceDenoiseFrame& frame,
                         vec3* direct, vec3* indirect) {
  using denoise::ConstRgbPlanes;
  using denoise::ConstSurfacePlanes;
  const ConstGBufferView g = frame.g;
  const int w = g.width, h = g.height;
  if (w <= 0 || h <= 0) return;
  const size_t n = size_t(w) * size_t(h);
  const bool has_indirect = indirect != nullptr;
  HistoryState state = frame.state;
  int prev_width = w, prev_height = h;
  if (width_ != w || height_ != h) {
    const bool keep_last = valid_ && state != HistoryState::kReset && settings.temporal;
    if (keep_last) {
      prev_width = width_;
      prev_height = height_;
    }
    resize(w, h, keep_last);
    if (!keep_last) {
      length_.resize(n);
      length_.fill_zero();
    }
  }
  const bool resized = prev_width != w || prev_height != h;
  if (!valid_ || had_indirect_ != has_indirect) state = HistoryState::kReset;
  valid_ = true;
  had_indirect_ = has_indirect;
  std::swap(surface_, prev_surface_);
  std::swap(packed_, prev_packed_);
  std::swap(history_, prev_history_);
  std::swap(length_, prev_length_);
  // (The swapped-in planes keep the size of the run that last wrote them; this run writes n.)
  surface_.depth.resize(n);
  surface_.nx.resize(n);
  surface_.ny.resize(n);
  surface_.nz.resize(n);
  surface_.object.resize(n);
  for (auto& p : packed_.w) p.resize(n);
  history_.resize(n);
  length_.resize(n);

  const DenoiseSettings& s = settings;
  const bool rest = denoise::denoise_at_rest(s, state);
  const denoise::TemporalSettings temporal_settings =
      denoise::temporal_settings(s, state, frame.indirect_history, resized, rest_valid_);
  const float cap_indirect = temporal_settings.cap_indirect;

  row_short_.fill_zero();
  {
    denoise::TemporalPass temporal;
    temporal.g = g;
    temporal.direct = direct;
    temporal.indirect = indirect;
    temporal.prev_surface = ConstSurfacePlanes(prev_surface_.view());
    temporal.prev_packed = denoise::ConstPackedPlanes(prev_packed_.view());
    temporal.prev = prev_history_.view();
    temporal.prev_length = prev_length_.data();
    temporal.next = history_.view();
    temporal.surface = surface_.view();
    temporal.packed = packed_.view();
    temporal.var_direct = var_direct_.data();
    temporal.var_indirect = var_indirect_.data();
    temporal.length = length_.data();
    temporal.width = w;
    temporal.height = h;
    temporal.prev_width = prev_width;
    temporal.prev_height = prev_height;
    temporal.s = temporal_settings;
    temporal.direct_region = frame.direct_region;
    const bool update_rest = rest || state == HistoryState::kReset;
    // (Reprojecting frames write the modulation from last frame's packed planes; at rest it is
    // averaged in place, as Denoiser::run.)
    temporal.rest = {rest_factor_.view(), rest_emission_.view()};
    uint32_t* row_short = row_short_.data();
    if (has_indirect)
      update_rest ? device_denoise::temporal<true, true>(temporal, row_short)
                  : device_denoise::temporal<true, false>(temporal, row_short);
    else
      update_rest ? device_denoise::temporal<false, true>(temporal, row_short)
                  : device_denoise::temporal<false, false>(temporal, row_short);
  }
  rest_valid_ = rest || state == HistoryState::kReset;
  rest_frames_ = rest && !resized ? denoise::next_count(rest_frames_) : 0;
  history_frames_ = state == HistoryState::kReset ? 0 : denoise::next_count(history_frames_);

  // The filter's input: the accumulated demodulated light, the history's.
  const denoise::HistoryPlanes history = history_.view();
  ConstRgbPlanes light_d = history.direct_light();
  ConstRgbPlanes light_i = history.indirect_light();
  const bool spatial = s.spatial && s.atrous_iterations > 0;
  const float* depth = surface_.depth.data();
  const denoise::AtrousPlan plan = denoise::atrous_plan(
      s, spatial, has_indirect, h, rest_frames_, history_frames_, temporal_settings.clipped());
  if (spatial) device_denoise::depth_slope(depth, w, h, depth_slope_.data());
  // (With the plan's half_variance, the half-resolution filter estimates it: filter_half.)
  if (spatial && !plan.half_variance) {
    denoise::BoxPass box;
    box.history = history;
    box.depth = depth;
    for (int k = 0; k < 5; ++k) box.sums[k] = box_[k].data();
    box.width = w;
    denoise::VariancePass variance;
    variance.depth = depth;
    variance.length = length_.data();
    for (int k = 0; k < 5; ++k) variance.sums[k] = box_[k].data();
    variance.var_direct = var_direct_.data();
    variance.var_indirect = var_indirect_.data();
    variance.width = w;
    variance.height = h;
    variance.cap_indirect = cap_indirect;
    device_denoise::spatial_variance(box, variance, row_short_.data());
  }
  const denoise::AtrousPass base =
      denoise::atrous_base(s, ConstSurfacePlanes(surface_.view()), depth_slope_.data(), light_d,
                           var_direct_.data(), light_i, var_indirect_.data(), w, h);
  const device_denoise::DevicePasses passes;
  denoise::FullPlanes full;
  for (int k = 0; k < 2; ++k) {
    full.direct[k] = filter_direct_[k].view();
    full.indirect[k] = filter_indirect_[k].view();
    full.direct_var[k] = filter_var_direct_[k].data();
    full.indirect_var[k] = filter_var_indirect_[k].data();
  }
  if (plan.direct_full) denoise::filter_direct_full(passes, base, plan, full, light_d, light_i);
  denoise::RemodulatePass remodulate{
      g,       {ConstRgbPlanes(rest_factor_.view()), ConstRgbPlanes(rest_emission_.view())},
      light_d, light_i,
      direct,  indirect};
  if (plan.direct_half || plan.half) {
    denoise::HalfPlanes half;
    half.surface = half_surface_.view();
    half.depth_slope = half_slope_.data();
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < denoise::kHalfMaxLights; ++l) {
        half.light[k][l] = half_light_[k][l].view();
        half.variance[k][l] = half_var_[k][l].data();
      }
    for (int l = 0; l < denoise::kHalfMaxLights; ++l) half.upsampled[l] = upsampled_[l].view();
    for (int k = 0; k < 5; ++k) half.moments[k] = half_moments_[k].data();
    half.width = half_width_;
    half.height = half_height_;
    const denoise::HalfVarianceInputs variance{history, length_.data(), cap_indirect,
                                               history_frames_ == 0};
    denoise::filter_half(passes, base, plan, half, variance, remodulate, rest, light_d, light_i);
  }
  if (plan.indirect_full) denoise::filter_indirect_full(passes, base, plan, full, light_i);
  if (plan.upsample_remodulates) return;
  remodulate.direct = light_d;
  remodulate.indirect = light_i;
  if (has_indirect)
    rest ? device_denoise::remodulate<true, true>(remodulate, n)
         : device_denoise::remodulate<true, false>(remodulate, n);
  else
    rest ? device_denoise::remodulate<false, true>(remodulate, n)
         : device_denoise::remodulate<false, false>(remodulate, n);
}

}  // namespace bounce
