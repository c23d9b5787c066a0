#include "bounce/techniques/tiled/tiled.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"
#include "bounce/render/memory_estimate.h"
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
  params_.add_int("motion_lowres", &s.motion_lowres, 1, 16,
                  "lowres of frames that gather the kept passes after a camera move");
  params_.add_bool("motion_edges", &s.motion_edges,
                   "those frames re-estimate edge pixels too (off: the denoiser stops at edges)");
  params_.add_int("tile", &s.tile, 1, 256, "screen tile size, pixels");
  params_.add_int("gather", &s.gather, 0, 1, "density estimation: 0 screen tiles, 1 hash grid");
  params_.add_float("slab", &s.slab, 0.0, 1.0, "tangent slab half-thickness / radius");
  params_.add_bool("leak_guard", &s.leak_guard, "clearance rays stop light through thin walls");
  params_.add_float("alpha", &s.alpha, 0.01, 1.0, "radius reduction of passes at rest");
  params_.add_int("history_passes", &s.history_passes, 1, 64,
                  "photon passes kept and gathered again after a camera move");
  params_.add_int("restart_passes", &s.restart_passes, 1, 16,
                  "photon passes per frame right after a change ends a still period (1: off)");
  params_.add_int("restart_frames", &s.restart_frames, 0, 64,
                  "frames after such a change that trace restart_passes passes");
  add_edge_params(params_, s.edges);
  params_.add_int("seed", &s.seed, 0, 1 << 30, "photon sample seed");
}

std::vector<TechniqueOption> TiledPhotonMapping::options() const {
  return {
      param_option("photons", "photons",
                   "Photon paths per frame (render: 20000 per pass unless given)"),
      {"radius", "Gather radius: scene units (0.05) or percent of the scene diagonal (3%)",
       [](ParamSet& params, const std::string& text) {
         if (text.empty() || text.back() != '%') return params.set("radius", text);
         // Percent of the diagonal, as the relative radius; the absolute one is turned off.
         const std::string number = text.substr(0, text.size() - 1);
         char* end = nullptr;
         const double percent = std::strtod(number.c_str(), &end);
         if (number.empty() || *end != '\0') fail("--radius: '{}' is not a percentage", text);
         params.set("radius_rel", fmt::format("{}", percent / 100.0));
         params.set("radius", "0");
       }},
      param_option("bounces", "bounces",
                   "Photon bounces: -1 = until Russian roulette ends the path, 1 = the seed's"),
      param_option("lowres", "lowres", "Indirect light at 1/N of the width and height"),
      param_option("tile", "tile", "Screen tile size in pixels (tile gather)"),
      {"gather", "Density estimation: tiles or grid",
       [](ParamSet& params, const std::string& text) {
         if (text != "tiles" && text != "grid")
           fail("--gather: '{}' is neither 'tiles' nor 'grid'", text);
         params.set("gather", text == "tiles" ? "0" : "1");
       }},
  };
}

std::vector<std::string> TiledPhotonMapping::still_defaults() const {
  // A still affords ten times the real-time frame's photons per pass, and each of its passes is
  // one pass (no boost after the first frame's restart).
  return {"photons=20000", "restart_passes=1"};
}

uint64_t TiledPhotonMapping::memory_estimate(const Scene& scene) const {
  const TiledSettings& s = settings_;
  const double passes = double(s.photons) * double(s.history_passes);
  // The ring of passes, and their union gathered again after a camera move.
  return saturating_bytes(passes * expected_photon_deposits(scene, s.bounces) *
                          double(kPhotonBufferBytes) * 2.0);
}

const PhotonBuffer& TiledPhotonMapping::photons() const {
  static const PhotonBuffer none;
  return history_.size() > 0 ? history_.newest() : none;
}

float TiledPhotonMapping::progressive_radius(float full_radius, float alpha, uint32_t passes) {
  float radius2 = full_radius * full_radius;
  for (uint32_t i = 1; i < passes; ++i) radius2 *= (float(i - 1) + alpha) / float(i);
  return std::sqrt(radius2);
}

float TiledPhotonMapping::frame_radius(float full_radius, float alpha, uint32_t fresh,
                                       uint32_t passes) {
  return fresh > 1 ? range_radius(full_radius, alpha, passes - fresh + 1, passes)
                   : progressive_radius(full_radius, alpha, passes);
}

PhotonTraceSettings TiledPhotonMapping::pass_trace_settings(const TiledSettings& s,
                                                            uint32_t frame_index, uint32_t k) {
  PhotonTraceSettings ts;
  ts.paths = uint32_t(s.photons);
  ts.max_bounces = s.bounces;
  ts.seed = uint32_t(s.seed);
  ts.pass = frame_index + k * 0x10000000u;
  return ts;
}

uint32_t RestartBoost::frame_passes(const TiledSettings& s, bool restart, bool accumulate,
                                    size_t capacity) {
  if (restart) {
    // A restart after a still period (the last one restart_frames or more frames ago) starts
    // the boost; under continuous change no frame gets it.
    const uint32_t boost_frames = uint32_t(s.restart_frames);
    boosted_frames_left = accumulate && frames_since_restart >= boost_frames ? boost_frames : 0;
    frames_since_restart = 0;
  }
  if (frames_since_restart < UINT32_MAX) ++frames_since_restart;
  if (boosted_frames_left == 0) return 1;
  --boosted_frames_left;
  return uint32_t(std::clamp<size_t>(size_t(s.restart_passes), 1, capacity));
}

float TiledPhotonMapping::union_radius(float full_radius, float alpha, uint32_t passes) {
  return range_radius(full_radius, alpha, 1, passes);
}

float TiledPhotonMapping::range_radius(float full_radius, float alpha, uint32_t first,
                                       uint32_t last) {
  double sum = 0.0;
  float radius2 = full_radius * full_radius;
  for (uint32_t i = 1; i <= last; ++i) {
    if (i >= first) sum += radius2;
    radius2 *= (float(i - 1) + alpha) / float(i);
  }
  const uint32_t count = last >= first ? last - first + 1 : 1;
  return float(std::sqrt(sum / double(count)));
}

TiledGatherView TiledPhotonMapping::gather_view(const GBuffer& g, const PhotonBuffer& photons,
                                                const GatherPlan& plan) const {
  TiledGatherView v;
  v.g = g.view();
  v.photons = photons.view();
  v.settings = {plan.radius, settings_.slab * plan.radius, settings_.leak_guard};
  v.use_grid = plan.grid;
  if (v.use_grid)
    v.grid = grid_.view();
  else
    v.bins = bins_.view();
  return v;
}

void TiledPhotonMapping::estimate(const FrameContext& c, const PhotonBuffer& photons,
                                  const GatherPlan& plan, Image& out) {
  const GBuffer& g = c.gbuffer;
  {
    ScopedStage stage(c.times, plan.grid ? "indirect/hash grid" : "indirect/tile bins");
    if (plan.grid)
      grid_.build(photons.position, plan.radius);
    else
      bins_.build(g, c.camera, photons, plan.radius, settings_.tile);
  }
  const TiledGatherView gather = gather_view(g, photons, plan);
  // Low resolution: bilinear upsampling of one gather per plan.lowres^2 block; pixels whose
  // normal or position disagrees with the interpolated one (edges) are gathered themselves.
  const EdgeTest edges = (plan.edges ? settings_.edges : EdgeSettings::none()).test(diagonal_);
  edge_pixels_ = estimate_at_low_res(
      gather.g, plan.lowres, edges, [gather](int x, int y) { return gather_pixel(gather, x, y); },
      low_, out.view(), c.times);
}

// Photons depend on the scene, not the pixels: they are traced (and their clearances found) in
// prepare, before the G-buffer. They stay valid while only the camera moves; any other change,
// or accumulation off, drops them and restarts at the full radius.
void TiledPhotonMapping::prepare(const PrepareContext& c) {
  diagonal_ = std::max(c.scene.bounds.diagonal(), 1e-6f);
  full_radius_ = settings_.radius > 0.0f ? settings_.radius : settings_.radius_rel * diagonal_;
  const size_t capacity = size_t(settings_.history_passes);
  const bool restart = !c.accumulate || c.change.world_changed() || history_.capacity() != capacity;
  if (restart) {
    history_.reset(capacity);
    passes_ = 0;
  }
  frame_passes_ = boost_.frame_passes(settings_, restart, c.accumulate, capacity);
  for (uint32_t k = 0; k < frame_passes_; ++k) {
    const PhotonTraceSettings ts = pass_trace_settings(settings_, c.frame_index, k);
    PhotonBuffer& photons = history_.add(ts.pass);
    {
      ScopedStage stage(c.times, "prepare/photon trace");
      const PhotonTraceStats stats = tracer_.trace(c.scene, c.scene_view, c.tracer, ts, photons);
      c.counters.photon_paths += stats.paths;
      c.counters.photons_stored += stats.stored;
      c.counters.rays += stats.rays;
    }
    if (settings_.leak_guard) {
      // Clearances out to the full radius serve every later, smaller radius: a gather within
      // radius r only asks whether the free distance reaches below r.
      ScopedStage stage(c.times, "prepare/clearance");
      c.counters.rays += compute_photon_clearance(c.tracer, full_radius_, photons);
    } else {
      photons.clearance.clear();
      photons.min_clearance.clear();
    }
  }
}

void TiledPhotonMapping::indirect(const FrameContext& c, Image& out) {
  // After a camera move (new pixels, same world) the per-pixel sum is rebuilt from every pass
  // kept; after a restart it is this frame's passes; otherwise it grows by this frame's passes.
  const bool restart = passes_ == 0;
  const bool moved = !restart && (c.change.camera || accumulated_.width() != out.width() ||
                                  accumulated_.height() != out.height());
  if (pass_estimate_.width() != out.width() || pass_estimate_.height() != out.height())
    pass_estimate_ = Image(out.width(), out.height());
  const uint32_t fresh = frame_passes_;  // prepare keeps it within the ring's capacity
  const uint32_t before = restart ? 0 : passes_;
  passes_ = moved ? uint32_t(history_.size()) : before + fresh;

  // Progressive photon mapping as the average of independent passes whose radius shrinks
  // (Knaus and Zwicker 2011). Passes gathered together share one radius, and their summed flux
  // gives the sum of their estimates.
  GatherPlan plan{frame_radius(full_radius_, settings_.alpha, fresh, passes_), settings_.lowres,
                  settings_.gather != 0};
  const PhotonBuffer* photons = &history_.newest();
  if (moved && passes_ > 1) {
    ScopedStage stage(c.times, "indirect/photon union");
    history_.concatenate(union_);
    photons = &union_;
    // Several passes' photons per gather: fewer gather points and the hash grid, whose build
    // costs next to nothing, keep the frame's cost bounded (README.md, "Photons kept across
    // camera moves").
    plan = {union_radius(full_radius_, settings_.alpha, passes_), settings_.motion_lowres, true,
            settings_.motion_edges};
  } else if (fresh > 1) {
    // A boosted frame: its passes gathered together at the mean of their discs.
    ScopedStage stage(c.times, "indirect/photon union");
    history_.concatenate(union_, fresh);
    photons = &union_;
  }
  last_radius_ = plan.radius;
  estimate(c, *photons, plan, pass_estimate_);

  const float inv_passes = 1.0f / float(passes_);
  if (restart || moved) {
    std::swap(accumulated_, pass_estimate_);
    parallel_for(
        out.pixel_count(),
        [&](size_t i) { out.pixels()[i] = accumulated_.pixels()[i] * inv_passes; }, 4096);
    return;
  }
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
