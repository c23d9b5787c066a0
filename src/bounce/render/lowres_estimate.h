// The CPU launch of lowres_kernels.h: a technique's per-pixel indirect estimate made at
// 1/factor of the resolution, upsampled, and re-estimated at full resolution on edges.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/image_view.h"
#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"
#include "bounce/core/timer.h"
#include "bounce/render/lowres_kernels.h"
#include "bounce/render/params.h"

namespace bounce {

// The edge test as a technique's settings keep it, relative to the scene's size.
struct EdgeSettings {
  float normal = 0.99f;    // re-estimate at full resolution below this normal agreement
  float distance = 0.01f;  // ... or beyond this position gap, relative to the scene diagonal
  bool show = false;       // debug view: re-estimated pixels in yellow
  bool misses = true;      // re-estimate where a blended sample missed (else blend those that hit)

  EdgeTest test(float diagonal) const { return {normal, distance * diagonal, show, misses}; }
  // No pixel re-estimated for its normal or position (only blocks whose sample misses): where
  // the denoiser's edge-stopping filter does the job.
  static EdgeSettings none() { return {-1.0f, 1.0f}; }
};

// `s` with misses blended rather than re-estimated.
inline EdgeSettings blend_misses(EdgeSettings s) {
  s.misses = false;
  return s;
}

// The edge test's parameters, under the same names for every technique that estimates at low
// resolution (edge_normal, edge_distance, show_edges).
inline void add_edge_params(ParamSet& params, EdgeSettings& s) {
  params.add_float("edge_normal", &s.normal, -1.0, 1.0, "edge test: normal agreement");
  params.add_float("edge_distance", &s.distance, 0.0, 1.0,
                   "edge test: position gap / scene diagonal");
  params.add_bool("show_edges", &s.show, "show re-estimated pixels in yellow");
  params.add_bool("edge_misses", &s.misses,
                  "edge test: re-estimate pixels whose blend takes a block sample that saw no "
                  "surface (else blend the samples that did)");
}

// The low-resolution samples, kept across frames so that their storage is reused.
struct LowResBuffers {
  int width = 0, height = 0;
  std::vector<vec3> radiance, normal, position;
  std::vector<uint8_t> valid;

  // Sized for a width x height frame at 1/factor; the view over the samples.
  LowResView resize(int full_width, int full_height, int factor) {
    width = (full_width + factor - 1) / factor;
    height = (full_height + factor - 1) / factor;
    const size_t n = size_t(width) * size_t(height);
    radiance.resize(n);
    normal.resize(n);
    position.resize(n);
    valid.resize(n);
    return {radiance.data(), normal.data(), position.data(), valid.data(), width, height, factor};
  }
};

// Writes `out` (the G-buffer's size) with estimate(x, y) at every pixel: directly when factor is
// 1, else through the low-resolution samples in `low` and the edge test. Returns the number of
// pixels estimated at full resolution as edges (0 at factor 1). The stages are timed as
// "indirect/estimate low-res" and "indirect/upsample + edges".
template <typename Estimate>
size_t estimate_at_low_res(const ConstGBufferView& g, int factor, const EdgeTest& edges,
                           const Estimate& estimate, LowResBuffers& low, const ImageView& out,
                           StageTimes& times) {
  if (factor <= 1) {
    parallel_for_2d(g.width, g.height, [&](int x, int y) { out.at(x, y) = estimate(x, y); });
    return 0;
  }
  const LowResView low_view = low.resize(g.width, g.height, factor);
  {
    ScopedStage stage(times, "indirect/estimate low-res");
    parallel_for_2d(low.width, low.height,
                    [&](int lx, int ly) { estimate_low_res(g, low_view, lx, ly, estimate); });
  }
  ScopedStage stage(times, "indirect/upsample + edges");
  const ConstLowResView low_read = low_view;
  // A task per row: the row blends its low-resolution columns once for all its pixels, then
  // each pixel blends its two; the edges are estimated after the row's blend, so that loop holds
  // no call. The views are copied in so that the compiler keeps their pointers in registers
  // (the estimator too: it must be copyable). The edges are counted row by row.
  return parallel_reduce(
      size_t(g.height), size_t(0),
      [&](size_t y) {
        const ConstGBufferView gv = g;
        const ConstLowResView l = low_read;
        const Estimate e = estimate;
        const int py = int(y);
        const UpsampleRow row = upsample_row(l, py);
        thread_local std::vector<UpsampleColumn> columns;
        thread_local std::vector<int> edge_x;
        columns.resize(size_t(l.width));
        for (int lx = 0; lx < l.width; ++lx) columns[size_t(lx)] = upsample_column(l, row, lx);
        edge_x.clear();
        for (int x = 0; x < gv.width; ++x) {
          const UpsampleSpan span = upsample_span(l, x);
          const Upsampled u = upsample_blend(gv, edges, gv.index(x, py), columns[size_t(span.lx0)],
                                             columns[size_t(span.lx1)], span.fx);
          out.at(x, py) = u.radiance;
          if (u.edge) edge_x.push_back(x);
        }
        for (const int x : edge_x) out.at(x, py) = edge_radiance(edges, x, py, e);
        return edge_x.size();
      },
      [](size_t a, size_t b) { return a + b; }, 4);
}

}  // namespace bounce
