// Technique "vertex": the pi-engine's real-time photon map estimated at the vertices of a refined
// mesh, after seed 004 (004_8db9349224acb88a.txt; notes/seed-004.md). See README.md beside this
// file for the frame, the parameters and the deviations.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/render/technique.h"
#include "bounce/techniques/vertex/photon_kdtree.h"
#include "bounce/techniques/vertex/photon_ring.h"
#include "bounce/techniques/vertex/refined_mesh.h"
#include "bounce/techniques/vertex/vertex_estimate.h"
#include "bounce/techniques/vertex/vertex_kernels.h"
#include "bounce/techniques/vertex/vertex_photons.h"

namespace bounce {

// The seed's 16 parameters (§7, by their names there) and the values it leaves open.
struct VertexSettings {
  bool bsp_tree = true;            // 1 BSP_tree: photon rays through the BVH, else every triangle
  int mesh_refinement = 10000;     // 2 triangles added by longest-edge splits
  bool use_estimate_cache = true;  // 3 one estimate per refined vertex, not per corner
  int max_search_count = 50;       // 4 k
  float max_search_radius = 0.0f;  // 5 scene units; 0: max_search_radius_rel * diagonal
  bool use_radius_heuristic = false;   // 6 r_max = sqrt(k r_n^2 / (alpha n)) (Eq 3.7)
  bool use_sphere_slice = true;        // 7
  bool final_gathering = false;        // 8
  int photons_from_light = 200;        // 9 photon paths per frame
  int accumulation_frames = 10;        // 10 ring slots
  bool store_direct_light = false;     // 11 (our direct stage computes direct light)
  int recursion_depth = 1;             // 12 split levels
  int diffuse_reflections = 36;        // 13 photons a split makes
  int snowball_size = 1;               // 14 photons stored per hit
  int light_distribution_type = 0;     // 15 0 Saff-Kuijlaars, 1 random (rejection)
  int diffuse_light_distribution = 0;  // 16 0 stratified, 1 random
  // What the seed leaves open.
  float max_search_radius_rel = 0.1f;  // of the scene diagonal
  float radius_heuristic_alpha = 0.05f;
  float slice_thickness_rel = 0.001f;  // half-thickness of the slice, of the scene diagonal
  int final_gathering_samples = 625;
  int stop_recursion_size = 8;         // kd-tree leaf bucket
  float snowball_radius_rel = 0.002f;  // of the scene diagonal
  bool direction_test = true;          // photons from the other side of a surface do not count
  bool roulette = true;                // beyond the split levels, paths go on by Russian roulette
  bool exact_photon_map = false;       // brute-force k nearest (the seed's Exact_photon_map)
  int seed = 0;
  // While a frame's photons equal the ones they replace (nothing that lights or holds them
  // moved), the kd-tree and the estimates already made stay: the same answers, not recomputed.
  bool keep_unchanged = true;
};

class VertexPhotonMapping final : public Technique {
 public:
  VertexPhotonMapping();
  std::string name() const override { return "vertex"; }
  std::vector<TechniqueOption> options() const override;
  std::vector<std::string> still_defaults() const override;
  // The photon ring, the map gathered from it and its kd-tree, and the refined mesh.
  uint64_t memory_estimate(const Scene& scene) const override;
  // Refines the mesh (first frame, new refinement) or moves its keys (moved meshes); traces this
  // frame's photons into the ring's slot and builds the kd-tree over the ring.
  void prepare(const PrepareContext& context) override;
  // Finds each pixel's refined triangle ("indirect/locate") band by band in the G-buffer pass.
  std::string begin_gbuffer_bands(const FrameContext& context) override;
  void gbuffer_band(int x0, int y0, int x1, int y1) override;
  // Estimates at the keys of the refined triangles the pixels see, and interpolates them.
  void indirect(const FrameContext& context, Image& out) override;
  bool indirect_overwrites() const override { return true; }  // (the interpolation)
  // A fresh estimate each frame from the ring of the last accumulation_frames photon frames.
  IndirectHistory indirect_history() const override { return IndirectHistory::kRing; }

  VertexSettings& settings() { return settings_; }
  const VertexSettings& settings() const { return settings_; }
  const RefinedMesh& refined() const { return refined_; }
  // The photons of the lights that stay put; those of lights that move (the flashlight) are
  // held apart, so that the first tree stands while only they change.
  const PhotonRing& ring() const { return still_.ring(); }
  const PhotonRing& moving_ring() const { return moving_.ring(); }
  // Both trees, searched as one.
  PhotonMapView photon_map() const { return {still_.tree().view(), moving_.tree().view()}; }
  size_t photon_count() const { return still_.tree().size() + moving_.tree().size(); }
  // The estimate settings of the last frame (radius, slice, flux scale).
  const EstimateSettings& estimate_settings() const { return estimate_; }
  // Irradiance estimates made in the last frame.
  uint64_t estimates() const { return estimates_; }
  // Whether the last frame kept the kd-tree of the lights that stay put (its photons equalled
  // those they replaced); that of the moving lights' photons.
  bool kept_tree() const { return still_.kept(); }
  bool kept_moving_tree() const { return moving_.kept(); }
  // Whether the last frame kept the still lights' photons of its slot instead of retracing
  // them (their frame-coherent paths, with nothing they depend on changed since they were traced).
  bool reused_still_photons() const { return reused_; }

 private:
  // Sizes the per-pixel and per-slot buffers for the context's G-buffer and the refined mesh;
  // returns the view the pixel kernels write them through.
  VertexPixelView pixel_buffers(const FrameContext& context);

  VertexSettings settings_;
  VertexSettings applied_;  // the settings the ring and refinement were made with
  bool started_ = false;
  int refined_with_ = -1;
  RefinedMesh refined_;
  // The photons of the lights that stay put, and of those that moved (moving_lights_).
  RingedPhotonTree still_, moving_;
  VertexPhotonTracer tracer_;
  // The scene's lights last frame, and per light whether it moved since the ring restarted.
  std::vector<Light> last_lights_;
  std::vector<uint8_t> moving_lights_;
  // Per ring slot, 1 + the frame its still lights' frame-coherent photons were traced in (0:
  // never, or a fresh set at rest); slots traced before still_fresh_since_ - 1 are out of date.
  std::vector<uint32_t> still_traced_;
  uint32_t still_fresh_since_ = 0;
  bool reused_ = false;
  EstimateSettings estimate_;
  uint32_t frame_ = 0;      // frames since the ring was reset
  uint32_t rest_pass_ = 0;  // frames at rest since the last change
  uint64_t estimates_ = 0;
  float diagonal_ = 1.0f;

  // Per pixel: its refined triangle, weights and side; per key (or corner) and side: whether a
  // pixel needs it, and its irradiance.
  std::vector<uint32_t> pixel_leaf_;
  std::vector<vec3> pixel_weights_;
  std::vector<uint8_t> pixel_side_;
  std::vector<uint8_t> needed_;
  std::vector<uint8_t> known_;  // estimated since the tree was built (keep_unchanged)
  std::vector<uint32_t> todo_;
  std::vector<vec3> irradiance_;
  // The pixels were located in the G-buffer pass (begin_gbuffer_bands), through this view.
  bool located_ = false;
  VertexPixelView located_view_{};
};

}  // namespace bounce
