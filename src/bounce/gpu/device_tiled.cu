#include <algorithm>
#include <span>

#include "bounce/gpu/device_scene.h"
#include "bounce/gpu/device_tiled.h"
#include "bounce/gpu/launch.h"
#include "bounce/techniques/tiled/tiled_kernels.h"

namespace bounce {

void DeviceTiled::prepare(const TiledSettings& settings, const DeviceScene& scene,
                          const SceneChange& change, bool accumulate, uint32_t frame_index,
                          TechniqueCounters& counters) {
  settings_ = settings;
  diagonal_ = std::max(scene.view().bounds.diagonal(), 1e-6f);
  full_radius_ = settings.radius > 0.0f ? settings.radius : settings.radius_rel * diagonal_;
  // As TiledPhotonMapping::prepare: the same boost after a restart of the world, the same
  // passes. Camera moves restart the average here too (the deviation above), without the boost.
  const bool world_restart = !accumulate || change.world_changed();
  if (world_restart || change.any()) passes_ = 0;
  frame_passes_ =
      boost_.frame_passes(settings, world_restart, accumulate, size_t(settings.history_passes));
  if (parts_.size() < frame_passes_) parts_.resize(frame_passes_);
  for (uint32_t k = 0; k < frame_passes_; ++k) {
    const PhotonTraceSettings ts =
        TiledPhotonMapping::pass_trace_settings(settings, frame_index, k);
    const DevicePhotonStats stats =
        tracer_.trace(scene, ts, frame_passes_ == 1 ? photons_ : parts_[k]);
    counters.photon_paths += stats.paths;
    counters.photons_stored += stats.stored;
    counters.rays += stats.rays;
  }
  if (frame_passes_ > 1)
    join_photons(std::span<const DevicePhotons>(parts_.data(), frame_passes_), photons_);
  if (settings.leak_guard && photons_.count > 0)
    counters.rays += tracer_.clearance(scene, full_radius_, photons_);
}

void DeviceTiled::indirect(const DeviceScene& scene, const ConstGBufferView& g,
                           const CameraRays& camera, vec3* out) {
  const size_t n = g.size();
  // As TiledPhotonMapping::indirect: a frame's passes gathered together at the mean of their
  // discs, their summed flux the sum of their estimates.
  const bool first = passes_ == 0;
  passes_ += frame_passes_;
  const float radius =
      TiledPhotonMapping::frame_radius(full_radius_, settings_.alpha, frame_passes_, passes_);
  TiledGatherView gather;
  gather.g = g;
  gather.photons = photons_.view();
  gather.settings = {radius, settings_.slab * radius, settings_.leak_guard};
  gather.use_grid = settings_.gather != 0;
  if (photons_.count > 0) {
    if (gather.use_grid) {
      grid_.build(photons_, radius);
      gather.grid = grid_.view();
    } else {
      bins_.build(g, camera, photons_, radius, settings_.tile);
      gather.bins = bins_.view();
    }
  }
  pass_.resize(n);
  const ImageView image{pass_.data(), g.width, g.height};
  const int f = settings_.lowres;
  if (photons_.count == 0) {
    pass_.fill_zero();
  } else if (f == 1) {
    launch_2d(g.width, g.height,
              [=] __device__(int x, int y) { image.at(x, y) = gather_pixel(gather, x, y); });
  } else {
    const int lw = (g.width + f - 1) / f, lh = (g.height + f - 1) / f;
    const size_t ln = size_t(lw) * lh;
    low_radiance_.resize(ln);
    low_normal_.resize(ln);
    low_position_.resize(ln);
    low_valid_.resize(ln);
    const LowResView low{low_radiance_.data(),
                         low_normal_.data(),
                         low_position_.data(),
                         low_valid_.data(),
                         lw,
                         lh,
                         f};
    launch_2d(lw, lh, [=] __device__(int lx, int ly) { estimate_low_res(gather, low, lx, ly); });
    const EdgeTest edges = settings_.edges.test(diagonal_);
    const ConstLowResView read = low;
    launch_2d(g.width, g.height, [=] __device__(int x, int y) {
      upsample_pixel(gather, read, edges, upsample_row(read, y), image, x, y);
    });
  }
  // Progressive photon mapping: the average of the passes since the last change.
  sum_.resize(n);
  vec3* sum = sum_.data();
  const vec3* pass = pass_.data();
  const float inv = 1.0f / float(passes_);
  launch(n, [=] __device__(uint32_t i) {
    const vec3 s = first ? pass[i] : sum[i] + pass[i];
    sum[i] = s;
    out[i] = s * inv;
  });
}

}  // namespace bounce
