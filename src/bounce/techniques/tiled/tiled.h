// Technique "tiled": real-time photon-mapped indirect diffuse light after seed 000
// (000_324acdd807aef684.txt; notes/seed-000.md), on the CPU. See README.md beside this file.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/render/lowres_estimate.h"
#include "bounce/render/photon_hash_grid.h"
#include "bounce/render/photon_tracing.h"
#include "bounce/render/technique.h"
#include "bounce/techniques/tiled/photon_history.h"
#include "bounce/techniques/tiled/tile_bins.h"
#include "bounce/techniques/tiled/tiled_kernels.h"

namespace bounce {

struct TiledSettings {
  int photons = 2000;        // photon paths per frame (the frame stays within 33 ms: README.md)
  float radius = 0.0f;       // gather radius in scene units; 0: radius_rel * scene diagonal
  float radius_rel = 0.03f;  // gather radius relative to the scene's bounding-box diagonal
  int bounces = -1;          // -1: multi-bounce ended by Russian roulette; B: bounces 1..B
  int lowres = 2;            // indirect estimated at 1/lowres width and height (1: full)
  int motion_lowres = 4;     // the same, in frames that gather the kept passes after a camera move
  // Whether those frames re-estimate edge pixels (`edges`) too. Off: there each edge pixel's
  // gather reads all the kept passes' photons, which cost 2-6 ms a frame at 512x512, and the
  // denoiser's filter stops at the same edges (README.md, "Photons kept across camera moves").
  bool motion_edges = false;
  int tile = 8;       // screen tile size of the tile gather, pixels
  int gather = 0;     // density estimation: 0 screen tiles (the seed's; faster here), 1 hash grid
  float slab = 0.1f;  // half-thickness of the tangent slab, relative to the radius
  bool leak_guard = true;     // per-photon clearance rays against light through thin walls
  float alpha = 2.0f / 3.0f;  // radius reduction of passes at rest (Knaus and Zwicker 2011)
  int history_passes = 8;     // photon passes kept and gathered again after a camera move
  // After a restart that ends a still period (a light or object moved once), the first
  // restart_frames frames trace restart_passes passes each, so the image settles in fewer frames
  // (README.md, "Settling after a change"). Under continuous change every frame restarts and
  // none is boosted, so an animation's frame time stays flat.
  int restart_passes = 3;
  int restart_frames = 3;
  EdgeSettings edges;  // which pixels a low-resolution estimate re-estimates at full resolution
  int seed = 0;
};

// The restart boost (TiledSettings::restart_passes), kept by each backend's technique: call
// frame_passes once per frame.
struct RestartBoost {
  // Frames since the last restart (the first frame counts as after a long still period), and
  // how many more frames trace restart_passes passes.
  uint32_t frames_since_restart = UINT32_MAX;
  uint32_t boosted_frames_left = 0;

  // The passes this frame traces; `restart`: the world restarted this frame (or accumulation
  // is off), `capacity`: the most passes a frame may trace.
  uint32_t frame_passes(const TiledSettings& s, bool restart, bool accumulate, size_t capacity);
};

class TiledPhotonMapping final : public Technique {
 public:
  TiledPhotonMapping();
  std::string name() const override { return "tiled"; }
  // With accumulation (FrameSettings::accumulate) passes with shrinking radii average into one
  // estimate, at rest and across camera moves.
  IndirectHistory indirect_history() const override { return IndirectHistory::kAccumulated; }
  std::vector<TechniqueOption> options() const override;
  std::vector<std::string> still_defaults() const override;
  // The photon passes held (history_passes of them) and their union after a camera move.
  uint64_t memory_estimate(const Scene& scene) const override;
  // Traces this frame's photons and their clearances (world space, before the G-buffer); keeps
  // the passes before it while only the camera moves, drops them on any other change.
  void prepare(const PrepareContext& context) override;
  // Bins the photons for the G-buffer's pixels, gathers them and averages the passes: the new
  // pass at rest, every pass still held after a camera move.
  void indirect(const FrameContext& context, Image& out) override;

  TiledSettings& settings() { return settings_; }
  const TiledSettings& settings() const { return settings_; }
  // Passes averaged into the current image (1 after a change of the world or without
  // accumulation; after a camera move, the passes still held).
  uint32_t passes() const { return passes_; }
  // The gather radius of the last frame, in scene units.
  float last_radius() const { return last_radius_; }
  // The gather radius of an estimate made of `passes` passes: the full radius shrunk as
  // r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1).
  static float progressive_radius(float full_radius, float alpha, uint32_t passes);
  // The radius at which `passes` kept passes are gathered together: its disc is the mean of their
  // progressive discs, so the union is at least as good as the average of their estimates
  // (README.md, "Photons kept across camera moves").
  static float union_radius(float full_radius, float alpha, uint32_t passes);
  // The same for passes first..last (1-based) gathered together: this frame's passes.
  static float range_radius(float full_radius, float alpha, uint32_t first, uint32_t last);
  // The gather radius of a frame that brings the estimate to `passes` passes with `fresh` new
  // ones: their range's (range_radius) when several are gathered together, else the
  // progressive radius.
  static float frame_radius(float full_radius, float alpha, uint32_t fresh, uint32_t passes);
  // Photon pass k of frame `frame_index`: the sample pattern follows the frame index, so that
  // frames are independent without accumulation and no two passes of an estimate share photons;
  // a boosted frame's extra passes take samples far from any frame's.
  static PhotonTraceSettings pass_trace_settings(const TiledSettings& s, uint32_t frame_index,
                                                 uint32_t k);
  // Photon passes this frame traced (restart_passes in the frames after a restart, else 1).
  uint32_t frame_passes() const { return frame_passes_; }
  // The full radius (of the first pass) in the last frame's scene.
  float full_radius() const { return full_radius_; }
  // The passes kept for reuse; the newest is this frame's.
  const PhotonHistory& history() const { return history_; }
  // This frame's photons (none before the first frame).
  const PhotonBuffer& photons() const;
  const TileBins& tile_bins() const { return bins_; }
  size_t edge_pixels() const { return edge_pixels_; }

 private:
  // How a frame gathers: a pass, or the kept passes after a camera move.
  struct GatherPlan {
    float radius = 0.0f;
    int lowres = 1;
    bool grid = false;  // the hash grid, else the screen tiles
    bool edges = true;  // re-estimate edge pixels (settings_.edges) at full resolution
  };
  void estimate(const FrameContext& context, const PhotonBuffer& photons, const GatherPlan& plan,
                Image& estimate);
  TiledGatherView gather_view(const GBuffer& g, const PhotonBuffer& photons,
                              const GatherPlan& plan) const;

  TiledSettings settings_;

  PhotonTracer tracer_;
  PhotonHistory history_;
  PhotonBuffer union_;  // the passes held, in one buffer, for the gather after a camera move
  TileBins bins_;
  PhotonHashGrid grid_;
  LowResBuffers low_;
  Image pass_estimate_;
  Image accumulated_;          // the sum of the passes' estimates
  uint32_t passes_ = 0;        // in accumulated_; 0: restart at the next frame
  uint32_t frame_passes_ = 1;  // traced by this frame's prepare, the newest in history_
  RestartBoost boost_;
  float full_radius_ = 0.0f;
  float last_radius_ = 0.0f;
  float diagonal_ = 1.0f;
  size_t edge_pixels_ = 0;
};

}  // namespace bounce
