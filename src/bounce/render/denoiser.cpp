#include "bounce/render/denoiser.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/render/denoise_kernels.h"

namespace bounce {

using denoise::ConstHistory;
using denoise::ConstRgbPlanes;
using denoise::ConstSurfacePlanes;
using denoise::History;
using denoise::RgbPlanes;
using denoise::SurfacePlanes;

namespace {

// Motion of this many pixels shows as 0 or 1 in the motion view.
constexpr float kMotionViewRange = 8.0f;

// Float planes of one image size.
template <int kCount>
struct Planes {
  std::array<std::vector<float>, kCount> planes;
  void resize(size_t n) {
    for (auto& p : planes) p.assign(n, 0.0f);
  }
  float* operator[](int k) { return planes[size_t(k)].data(); }
  const float* operator[](int k) const { return planes[size_t(k)].data(); }
  RgbPlanes rgb(int first) { return {(*this)[first], (*this)[first + 1], (*this)[first + 2]}; }
  ConstRgbPlanes rgb(int first) const {
    return {(*this)[first], (*this)[first + 1], (*this)[first + 2]};
  }
};

// A frame's surfaces: depth, normal and object id.
struct SurfaceBuffers {
  Planes<4> geometry;
  std::vector<uint32_t> object;
  void resize(size_t n) {
    geometry.resize(n);
    object.assign(n, kNoPrimitive);
  }
  SurfacePlanes view() {
    return {geometry[0], geometry[1], geometry[2], geometry[3], object.data()};
  }
  ConstSurfacePlanes view() const {
    return {geometry[0], geometry[1], geometry[2], geometry[3], object.data()};
  }
};

// A frame's history but its length (Denoiser::history_length_ and Buffers::prev_length).
enum HistoryPlane {
  kDirect = 0,    // rgb
  kIndirect = 3,  // rgb
  kDirectM1 = 6,
  kDirectM2,
  kIndirectM1,
  kIndirectM2,
  kFactor = 10,    // rgb
  kEmission = 13,  // rgb
  kHistoryPlanes = 16,
};

template <typename View, typename P>
View history_view(P& planes, auto* length) {
  return {planes.rgb(kDirect), planes.rgb(kIndirect), planes[kDirectM1],
          planes[kDirectM2],   planes[kIndirectM1],   planes[kIndirectM2],
          planes.rgb(kFactor), planes.rgb(kEmission), length};
}

// The a-trous planes: direct rgb, indirect rgb, their variances.
enum FilterPlane { kFilterDirect = 0, kFilterIndirect = 3, kVarDirect = 6, kVarIndirect = 7 };

// Runs body(y) for every row, rows spread over the cores.
template <typename Body>
void for_rows(int height, const Body& body) {
  parallel_for(
      size_t(height), [&](size_t y) { body(int(y)); }, 2);
}

// One a-trous pass over the image: the interior of each row without column tests, which the
// compiler vectorises (the pass reads one set of planes and writes another).
template <int kRadius, bool kIndirect>
void atrous_pass(const denoise::AtrousPass& pass) {
  for_rows(pass.height, [&](int y) {
    const denoise::AtrousPass p = pass;
    const denoise::AtrousRows<kRadius> rows = denoise::atrous_rows<kRadius>(p, y);
    const int border = std::min(kRadius * p.step, p.width);
    const int x_end = std::max(p.width - kRadius * p.step, border);
    for (int x = 0; x < border; ++x) denoise::atrous_pixel<kRadius, kIndirect, true>(p, rows, x);
#pragma GCC ivdep
    for (int x = border; x < x_end; ++x)
      denoise::atrous_pixel<kRadius, kIndirect, false>(p, rows, x);
    for (int x = x_end; x < p.width; ++x)
      denoise::atrous_pixel<kRadius, kIndirect, true>(p, rows, x);
  });
}

}  // namespace

struct Denoiser::Buffers {
  int width = 0;
  int height = 0;
  bool valid = false;         // a previous run left a history of this size
  bool had_indirect = false;  // and it had indirect light
  Planes<6> raw;              // this frame demodulated: direct rgb, indirect rgb
  SurfaceBuffers surface, prev_surface;
  Planes<kHistoryPlanes> history, prev_history;
  std::vector<float> prev_length;
  std::vector<float> depth_slope;
  Planes<8> variance;                 // the variance pass's output: kVarDirect, kVarIndirect used
  Planes<8> filter[2];                // a-trous ping-pong
  const Planes<8>* result = nullptr;  // where the last run's filtered light is (null: history)
  std::vector<vec2> motion;
  Image raw_direct, raw_indirect;

  void resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h);
    raw.resize(n);
    surface.resize(n);
    prev_surface.resize(n);
    history.resize(n);
    prev_history.resize(n);
    prev_length.assign(n, 0.0f);
    depth_slope.assign(n, 0.0f);
    variance.resize(n);
    filter[0].resize(n);
    filter[1].resize(n);
    motion.assign(n, vec2(0.0f));
    valid = false;
  }
};

Denoiser::Denoiser() : buffers_(std::make_unique<Buffers>()) {
  DenoiseSettings& s = settings_;
  params_.add_bool("temporal", &s.temporal, "accumulate light over frames through reprojection");
  params_.add_bool("spatial", &s.spatial, "edge-avoiding a-trous filter of the light");
  params_.add_int("atrous_iterations", &s.atrous_iterations, 0, 8,
                  "a-trous passes, with steps 1, 2, 4, ... pixels");
  params_.add_float("sigma_luminance", &s.sigma_luminance, 0.01, 1000.0,
                    "luminance edge-stopping, in standard deviations of the estimate");
  params_.add_float("sigma_normal", &s.sigma_normal, 1.0, 1024.0,
                    "normal edge-stopping exponent on the cosine between normals");
  params_.add_float("sigma_depth", &s.sigma_depth, 0.01, 1000.0,
                    "depth edge-stopping, relative to the local depth slope");
  params_.add_int("history_max", &s.history_max, 1, 4096,
                  "frames of history a pixel keeps while anything moves");
  params_.add_int("accumulated_history", &s.accumulated_history, 1, 4096,
                  "frames of history for indirect light the technique accumulates itself");
  params_.add_float("clip_gamma", &s.clip_gamma, 0.0, 100.0,
                    "history clamp half-width in standard deviations when the world changed");
  params_.add_float("depth_tolerance", &s.depth_tolerance, 0.0, 10.0,
                    "reprojection: largest relative depth difference of the same surface");
  params_.add_float("normal_tolerance", &s.normal_tolerance, -1.0, 1.0,
                    "reprojection: smallest cosine between normals of the same surface");
}

Denoiser::~Denoiser() = default;

void Denoiser::run(const DenoiseFrame& frame, Image& direct, Image* indirect) {
  const GBuffer& gbuffer = frame.gbuffer;
  const int w = gbuffer.width, h = gbuffer.height;
  if (direct.width() != w || direct.height() != h)
    fail("denoiser: direct light is {}x{}, the G-buffer {}x{}", direct.width(), direct.height(), w,
         h);
  if (indirect && (indirect->width() != w || indirect->height() != h))
    fail("denoiser: indirect light is {}x{}, the G-buffer {}x{}", indirect->width(),
         indirect->height(), w, h);
  Buffers& b = *buffers_;
  const size_t n = size_t(w) * size_t(h);
  const bool has_indirect = indirect != nullptr;
  HistoryState state = frame.state;
  if (b.width != w || b.height != h) {
    b.resize(w, h);
    history_length_.assign(n, 0.0f);
  }
  if (!b.valid || b.had_indirect != has_indirect) state = HistoryState::kReset;
  b.valid = true;
  b.had_indirect = has_indirect;
  // Copies of this frame's input for the raw view, dropped when not asked for.
  b.raw_direct = keep_raw_ ? direct : Image();
  b.raw_indirect = keep_raw_ && indirect ? *indirect : Image();
  // Last run's "next" is this run's "previous".
  std::swap(b.surface, b.prev_surface);
  std::swap(b.history, b.prev_history);
  std::swap(history_length_, b.prev_length);

  const DenoiseSettings& s = settings_;
  const bool rest = state == HistoryState::kRest;
  const float cap_direct =
      rest ? std::numeric_limits<float>::infinity() : float(std::max(s.history_max, 1));
  const float cap_indirect = frame.indirect_accumulated
                                 ? std::min(cap_direct, float(std::max(s.accumulated_history, 1)))
                                 : cap_direct;
  const History next = history_view<History>(b.history, history_length_.data());
  const ConstHistory prev = history_view<ConstHistory>(std::as_const(b.prev_history),
                                                       std::as_const(b.prev_length).data());
  {
    ScopedStage stage(frame.times, "denoise/temporal");
    const denoise::DemodulatePass demodulate{
        gbuffer.view(), direct.data(), indirect ? indirect->data() : nullptr,
        b.raw.rgb(0),   b.raw.rgb(3),  b.surface.view(),
        b.motion.data()};
    parallel_for(
        n, [&](size_t i) { denoise::demodulate_pixel(demodulate, i); }, 2048);

    denoise::TemporalSettings ts;
    ts.history = s.temporal && state != HistoryState::kReset;
    ts.reproject = state == HistoryState::kCameraMoved || state == HistoryState::kWorldChanged;
    ts.clip = state == HistoryState::kWorldChanged;
    ts.has_indirect = has_indirect;
    ts.cap_direct = cap_direct;
    ts.cap_indirect = cap_indirect;
    ts.clip_gamma = s.clip_gamma;
    ts.depth_tolerance = s.depth_tolerance;
    ts.normal_tolerance = s.normal_tolerance;
    const denoise::TemporalPass temporal{gbuffer.view(),
                                         std::as_const(b.raw).rgb(0),
                                         std::as_const(b.raw).rgb(3),
                                         b.surface.view(),
                                         std::as_const(b.prev_surface).view(),
                                         prev,
                                         next,
                                         w,
                                         h,
                                         ts};
    for_rows(h, [&](int y) {
      for (int x = 0; x < w; ++x) denoise::temporal_pixel(temporal, x, y);
    });
  }

  const ConstHistory accumulated = next;
  ConstRgbPlanes light_d = accumulated.direct, light_i = accumulated.indirect;
  b.result = nullptr;
  const bool spatial = s.spatial && s.atrous_iterations > 0;
  if (spatial) {
    ScopedStage stage(frame.times, "denoise/variance");
    const denoise::VariancePass variance{b.surface.view(),
                                         accumulated,
                                         b.depth_slope.data(),
                                         b.variance[kVarDirect],
                                         b.variance[kVarIndirect],
                                         w,
                                         h,
                                         has_indirect,
                                         cap_indirect,
                                         s.sigma_normal,
                                         s.sigma_depth};
    for_rows(h, [&](int y) {
      for (int x = 0; x < w; ++x) denoise::variance_pixel(variance, x, y);
    });
  } else {
    std::fill_n(b.variance[kVarDirect], n, 0.0f);
    std::fill_n(b.variance[kVarIndirect], n, 0.0f);
  }
  {
    ScopedStage stage(frame.times, "denoise/atrous");
    if (spatial) {
      const float* var_d = b.variance[kVarDirect];
      const float* var_i = b.variance[kVarIndirect];
      for (int k = 0; k < s.atrous_iterations; ++k) {
        Planes<8>& out = b.filter[k & 1];
        const denoise::AtrousPass pass{b.surface.view(),
                                       b.depth_slope.data(),
                                       light_d,
                                       light_i,
                                       var_d,
                                       var_i,
                                       out.rgb(kFilterDirect),
                                       out.rgb(kFilterIndirect),
                                       out[kVarDirect],
                                       out[kVarIndirect],
                                       w,
                                       h,
                                       1 << k,
                                       s.sigma_luminance,
                                       s.sigma_normal,
                                       s.sigma_depth};
        if (has_indirect)
          atrous_pass<1, true>(pass);
        else
          atrous_pass<1, false>(pass);
        const Planes<8>& result = out;
        light_d = result.rgb(kFilterDirect);
        light_i = result.rgb(kFilterIndirect);
        var_d = result[kVarDirect];
        var_i = result[kVarIndirect];
        b.result = &result;
      }
    }
    const denoise::RemodulatePass remodulate{
        b.surface.view(), accumulated,   light_d,
        light_i,          direct.data(), indirect ? indirect->data() : nullptr};
    parallel_for(
        n, [&](size_t i) { denoise::remodulate_pixel(remodulate, i); }, 2048);
  }
}

void Denoiser::debug_view(DenoiseView view, Image& out) const {
  const Buffers& b = *buffers_;
  const int w = b.width, h = b.height;
  if (out.width() != w || out.height() != h) out = Image(w, h);
  const size_t n = size_t(w) * size_t(h);
  const ConstHistory history = history_view<ConstHistory>(b.history, history_length_.data());
  vec3* pixels = out.data();
  switch (view) {
    case DenoiseView::kDenoised: {
      const ConstRgbPlanes d = b.result ? b.result->rgb(kFilterDirect) : history.direct;
      const ConstRgbPlanes ind = b.result ? b.result->rgb(kFilterIndirect) : history.indirect;
      const bool has_indirect = b.had_indirect;
      parallel_for(n, [&](size_t i) {
        const vec3 f = history.factor.get(i);
        pixels[i] =
            d.get(i) * f + history.emission.get(i) + (has_indirect ? ind.get(i) * f : vec3(0.0f));
      });
      return;
    }
    case DenoiseView::kRaw:
      if (b.raw_direct.empty()) fail("denoiser: the raw view needs keep_raw(true) before the run");
      out = b.raw_direct;
      if (!b.raw_indirect.empty()) out += b.raw_indirect;
      return;
    case DenoiseView::kHistory: {
      const float inv_max = 1.0f / float(std::max(settings_.history_max, 1));
      parallel_for(
          n, [&](size_t i) { pixels[i] = vec3(std::min(history_length_[i] * inv_max, 1.0f)); });
      return;
    }
    case DenoiseView::kMotion:
      parallel_for(n, [&](size_t i) {
        const vec2 m = glm::clamp(0.5f + b.motion[i] / (2.0f * kMotionViewRange), 0.0f, 1.0f);
        pixels[i] = vec3(m.x, m.y, 0.0f);
      });
      return;
    case DenoiseView::kVariance: {
      const float* var_d = b.variance[kVarDirect];
      const float* var_i = b.variance[kVarIndirect];
      const bool has_indirect = b.had_indirect;
      parallel_for(n, [&](size_t i) {
        pixels[i] = vec3(std::sqrt(var_d[i] + (has_indirect ? var_i[i] : 0.0f)));
      });
      return;
    }
  }
}

}  // namespace bounce
