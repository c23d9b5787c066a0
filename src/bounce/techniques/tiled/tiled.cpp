#include "bounce/techniques/tiled/tiled.h"

#include <cmath>

#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"
#include "bounce/render/photon_clearance.h"
#include "bounce/render/photon_gather.h"

namespace bounce {

TiledPhotonMapping::TiledPhotonMapping() {
  TiledSettings& s = settings_;
  params_.add_int("photons", &s.photons, 1, 10000000, "photon paths per frame");
  params_.add_float("radius", &s.radius, 0.0, 1e9, "gather radius (scene units; 0: radius_rel)");
  params_.add_float("radius_rel", &s.radius_rel, 1e-6, 1.0, "gather radius / scene diagonal");
  params_.add_int("bounces", &s.bounces, -1, kMaxPhotonDepth,
                  "photon bounces (-1: until Russian roulette ends the path)");
  params_.add_int("lowres", &s.lowres, 1, 16, "indirect at 1/lowres of the width and height");
  params_.add_int("tile", &s.tile, 1, 256, "screen tile size, pixels");
  params_.add_int("gather", &s.gather, 0, 1, "density estimation: 0 screen tiles, 1 hash grid");
  params_.add_float("slab", &s.slab, 0.0, 1.0, "tangent slab half-thickness / radius");
  params_.add_bool("leak_guard", &s.leak_guard, "clearance rays stop light through thin walls");
  params_.add_bool("progressive", &s.progressive, "at rest, add photons and shrink the radius");
  params_.add_float("alpha", &s.alpha, 0.01, 1.0, "progressive radius reduction");
  params_.add_float("edge_normal", &s.edge_normal, -1.0, 1.0, "edge test: normal agreement");
  params_.add_float("edge_distance", &s.edge_distance, 0.0, 1.0,
                    "edge test: position gap / scene diagonal");
  params_.add_bool("show_edges", &s.show_edges, "show re-estimated pixels in yellow");
  params_.add_int("seed", &s.seed, 0, 1 << 30, "photon sample seed");
}

void TiledPhotonMapping::scene_changed(const Scene& scene, const Tracer& tracer) {
  scene_dirty_ = true;
  scene_data_stale_ = true;
}

bool TiledPhotonMapping::restart_needed(const FrameContext& c) const {
  if (scene_dirty_ || passes_ == 0 || !settings_.progressive) return true;
  if (!(settings_ == last_settings_)) return true;
  if (c.gbuffer.width != last_width_ || c.gbuffer.height != last_height_) return true;
  return !(c.camera == last_camera_);
}

TiledGatherView TiledPhotonMapping::gather_view(const GBuffer& g, float radius) const {
  TiledGatherView v;
  v.g = g.view();
  v.photons = photons_.view();
  v.settings = {radius, slab_, settings_.leak_guard};
  v.use_grid = settings_.gather != 0;
  if (v.use_grid)
    v.grid = grid_.view();
  else
    v.bins = bins_.view();
  return v;
}

void TiledPhotonMapping::estimate(const FrameContext& c, float radius, Image& out) {
  const GBuffer& g = c.gbuffer;
  const TiledGatherView gather = gather_view(g, radius);
  const ImageView image = out.view();
  const int f = settings_.lowres;
  if (f == 1) {
    parallel_for_2d(g.width, g.height,
                    [&](int x, int y) { image.at(x, y) = gather_pixel(gather, x, y); });
    edge_pixels_ = 0;
    return;
  }
  // Low resolution: estimate at one full-resolution pixel near the centre of each f x f block.
  LowRes& low = low_;
  low.width = (g.width + f - 1) / f;
  low.height = (g.height + f - 1) / f;
  const size_t n = size_t(low.width) * low.height;
  low.radiance.resize(n);
  low.normal.resize(n);
  low.position.resize(n);
  low.valid.resize(n);
  const LowResView low_view{low.radiance.data(),
                            low.normal.data(),
                            low.position.data(),
                            low.valid.data(),
                            low.width,
                            low.height,
                            f};
  {
    ScopedStage stage(c.times, "indirect/estimate low-res");
    parallel_for_2d(low.width, low.height,
                    [&](int lx, int ly) { estimate_low_res(gather, low_view, lx, ly); });
  }
  // Bilinear upsampling; where the interpolated normal or position disagrees with the pixel's
  // own (an edge), estimate the pixel at full resolution.
  ScopedStage stage(c.times, "indirect/upsample + edges");
  const EdgeTest edges{settings_.edge_normal, settings_.edge_distance * diagonal_,
                       settings_.show_edges};
  const ConstLowResView low_read{low.radiance.data(),
                                 low.normal.data(),
                                 low.position.data(),
                                 low.valid.data(),
                                 low.width,
                                 low.height,
                                 f};
  // A task per row: the row's interpolation weights are shared, and the views are copied in so
  // that the compiler keeps their pointers in registers. The edges are counted row by row.
  edge_pixels_ = parallel_reduce(
      size_t(g.height), size_t(0),
      [&](size_t y) {
        const TiledGatherView v = gather;
        const ConstLowResView l = low_read;
        const UpsampleRow row = upsample_row(l, int(y));
        size_t edge_count = 0;
        for (int x = 0; x < g.width; ++x)
          edge_count += upsample_pixel(v, l, edges, row, image, x, int(y)) ? 1 : 0;
        return edge_count;
      },
      [](size_t a, size_t b) { return a + b; }, 4);
}

void TiledPhotonMapping::indirect(const FrameContext& c, Image& out) {
  diagonal_ = std::max(c.scene.bounds.diagonal(), 1e-6f);
  const float base = settings_.radius > 0.0f ? settings_.radius : settings_.radius_rel * diagonal_;
  if (restart_needed(c)) {
    passes_ = 0;
    radius2_ = base * base;
    accumulated_ = Image(out.width(), out.height());
    last_settings_ = settings_;
    last_camera_ = c.camera;
    last_width_ = c.gbuffer.width;
    last_height_ = c.gbuffer.height;
    scene_dirty_ = false;
  }
  const float radius = std::sqrt(radius2_);
  last_radius_ = radius;
  slab_ = settings_.slab * radius;

  {
    ScopedStage stage(c.times, "indirect/photon trace");
    PhotonTraceSettings ts;
    ts.paths = uint32_t(settings_.photons);
    ts.max_bounces = settings_.bounces;
    ts.seed = uint32_t(settings_.seed);
    ts.pass = passes_;
    if (scene_data_stale_) {
      scene_data_.build(c.scene);
      scene_data_stale_ = false;
    }
    const PhotonTraceStats stats =
        tracer_.trace(c.scene, scene_data_.view(), c.tracer, ts, photons_);
    c.counters.photon_paths += stats.paths;
    c.counters.photons_stored += stats.stored;
    c.counters.rays += stats.rays;
  }
  if (settings_.leak_guard) {
    ScopedStage stage(c.times, "indirect/clearance");
    c.counters.rays += compute_photon_clearance(c.tracer, radius, photons_);
  } else {
    photons_.clearance.clear();
  }
  {
    ScopedStage stage(c.times, settings_.gather == 0 ? "indirect/tile bins" : "indirect/hash grid");
    if (settings_.gather == 0)
      bins_.build(c.gbuffer, c.camera, photons_, radius, settings_.tile);
    else
      grid_.build(photons_.position, radius);
  }
  if (pass_estimate_.width() != out.width() || pass_estimate_.height() != out.height())
    pass_estimate_ = Image(out.width(), out.height());
  estimate(c, radius, pass_estimate_);

  // Progressive photon mapping as the average of independent passes whose radius shrinks
  // (Knaus and Zwicker 2011): r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1).
  ++passes_;
  radius2_ *= (float(passes_ - 1) + settings_.alpha) / float(passes_);
  const float inv_passes = 1.0f / float(passes_);
  parallel_for(
      out.pixel_count(),
      [&](size_t i) {
        vec3& sum = accumulated_.pixels()[i];
        sum += pass_estimate_.pixels()[i];
        out.pixels()[i] = sum * inv_passes;
      },
      4096);
}

}  // namespace bounce
