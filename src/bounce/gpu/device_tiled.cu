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
  // As TiledPhotonMapping::prepare: a restart of the world after a still period boosts the next
  // restart_frames frames to restart_passes passes each. Camera moves restart the average here
  // too (the deviation above), without the boost.
  const bool world_restart = !accumulate || change.world_changed();
  if (world_restart) {
    const uint32_t boost_frames = uint32_t(settings.restart_frames);
    boosted_frames_left_ = accumulate && frames_since_restart_ >= boost_frames ? boost_frames : 0;
    frames_since_restart_ = 0;
  }
  if (world_restart || change.any()) passes_ = 0;
  if (frames_since_restart_ < UINT32_MAX) ++frames_since_restart_;
  frame_passes_ = 1;
  if (boosted_frames_left_ > 0) {
    --boosted_frames_left_;
    frame_passes_ = uint32_t(std::clamp(settings.restart_passes, 1, settings.history_passes));
  }
  if (parts_.size() < frame_passes_) parts_.resize(frame_passes_);
  for (uint32_t k = 0; k < frame_passes_; ++k) {
    // The CPU's sample numbers: the frame index, and far from any frame's for the extra passes.
    PhotonTraceSettings ts;
    ts.paths = uint32_t(settings.photons);
    ts.max_bounces = settings.bounces;
    ts.seed = uint32_t(settings.seed);
    ts.pass = frame_index + k * 0x10000000u;
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
  const uint32_t before = passes_;
  passes_ += frame_passes_;
  const float radius =
      frame_passes_ > 1
          ? TiledPhotonMapping::range_radius(full_radius_, settings_.alpha, before + 1, passes_)
          : TiledPhotonMapping::progressive_radius(full_radius_, settings_.alpha, passes_);
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
  const bool first = before == 0;
  const float inv = 1.0f / float(passes_);
  launch(n, [=] __device__(uint32_t i) {
    const vec3 s = first ? pass[i] : sum[i] + pass[i];
    sum[i] = s;
    out[i] = s * inv;
  });
}

}  // namespace bounce
