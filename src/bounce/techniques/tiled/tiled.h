// Technique "tiled": real-time photon-mapped indirect diffuse light after seed 000
// (000_324acdd807aef684.txt; notes/seed-000.md), on the CPU. See README.md beside this file.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/render/photon_hash_grid.h"
#include "bounce/render/photon_tracing.h"
#include "bounce/render/technique.h"
#include "bounce/techniques/tiled/tile_bins.h"
#include "bounce/techniques/tiled/tiled_kernels.h"

namespace bounce {

struct TiledSettings {
  int photons = 2000;        // photon paths per frame (the frame stays within 33 ms: README.md)
  float radius = 0.0f;       // gather radius in scene units; 0: radius_rel * scene diagonal
  float radius_rel = 0.03f;  // gather radius relative to the scene's bounding-box diagonal
  int bounces = -1;          // -1: multi-bounce ended by Russian roulette; B: bounces 1..B
  int lowres = 2;            // indirect estimated at 1/lowres width and height (1: full)
  int tile = 8;              // screen tile size of the tile gather, pixels
  int gather = 0;     // density estimation: 0 screen tiles (the seed's; faster here), 1 hash grid
  float slab = 0.1f;  // half-thickness of the tangent slab, relative to the radius
  bool leak_guard = true;       // per-photon clearance rays against light through thin walls
  float alpha = 2.0f / 3.0f;    // radius reduction of passes at rest (Knaus and Zwicker 2011)
  float edge_normal = 0.99f;    // re-estimate at full resolution below this normal agreement
  float edge_distance = 0.01f;  // ... or beyond this position gap, relative to the diagonal
  bool show_edges = false;      // debug view: re-estimated pixels in yellow
  int seed = 0;
};

class TiledPhotonMapping final : public Technique {
 public:
  TiledPhotonMapping();
  std::string name() const override { return "tiled"; }
  // At rest (FrameSettings::accumulate) passes with shrinking radii average into one estimate.
  IndirectHistory indirect_history() const override { return IndirectHistory::kAccumulated; }
  std::vector<TechniqueOption> options() const override;
  std::vector<std::string> still_defaults() const override;
  // Traces this frame's photons and their clearances (world space, before the G-buffer).
  void prepare(const PrepareContext& context) override;
  // Bins the photons for the G-buffer's pixels, gathers and averages the passes at rest.
  void indirect(const FrameContext& context, Image& out) override;

  TiledSettings& settings() { return settings_; }
  // Passes averaged into the current image (1 after any change or without accumulation).
  uint32_t passes() const { return passes_; }
  // The gather radius of the last pass, in scene units.
  float last_radius() const { return last_radius_; }
  const PhotonBuffer& photons() const { return photons_; }
  const TileBins& tile_bins() const { return bins_; }
  size_t edge_pixels() const { return edge_pixels_; }

 private:
  struct LowRes {
    int width = 0, height = 0;
    std::vector<vec3> radiance, normal, position;
    std::vector<uint8_t> valid;
  };
  void estimate(const FrameContext& context, float radius, Image& estimate);
  TiledGatherView gather_view(const GBuffer& g, float radius) const;

  TiledSettings settings_;

  PhotonTracer tracer_;
  PhotonBuffer photons_;
  TileBins bins_;
  PhotonHashGrid grid_;
  LowRes low_;
  Image pass_estimate_;
  Image accumulated_;
  uint32_t passes_ = 0;
  float radius2_ = 0.0f;  // squared radius of the next pass
  float last_radius_ = 0.0f;
  float diagonal_ = 1.0f;
  float slab_ = 0.0f;
  size_t edge_pixels_ = 0;
};

}  // namespace bounce
