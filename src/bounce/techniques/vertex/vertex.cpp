#include "bounce/techniques/vertex/vertex.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bounce/core/parallel.h"
#include "bounce/render/memory_estimate.h"
#include "bounce/techniques/vertex/vertex_kernels.h"

namespace bounce {

VertexPhotonMapping::VertexPhotonMapping() {
  VertexSettings& s = settings_;
  params_.add_bool("BSP_tree", &s.bsp_tree,
                   "photon rays through the BVH (false: test every triangle)");
  params_.add_int("mesh_refinement", &s.mesh_refinement, 0, 4000000,
                  "triangles added to the render mesh by longest-edge splits");
  params_.add_bool("use_estimate_cache", &s.use_estimate_cache,
                   "one estimate per refined vertex (false: per triangle corner)");
  params_.add_int("max_search_count", &s.max_search_count, 1, kMaxSearchCount,
                  "k: photons in one estimate");
  params_.add_float("max_search_radius", &s.max_search_radius, 0.0, 1e9,
                    "search radius, scene units (0: max_search_radius_rel)");
  params_.add_bool("use_radius_heuristic", &s.use_radius_heuristic,
                   "radius from k, the map's size and extent (Eq 3.7)");
  params_.add_bool("use_sphere_slice", &s.use_sphere_slice,
                   "only photons near the tangent plane count");
  params_.add_bool("final_gathering", &s.final_gathering,
                   "irradiance from gather rays into the photon map");
  params_.add_int("photons_from_light", &s.photons_from_light, 1, 10000000,
                  "photon paths per frame");
  params_.add_int("accumulation_frames", &s.accumulation_frames, 1, 1024,
                  "frames of photons in the map (ring slots)");
  params_.add_bool("store_direct_light", &s.store_direct_light,
                   "store first hits too (the direct stage adds direct light again)");
  params_.add_int("recursion_depth", &s.recursion_depth, 0, kMaxRecursionDepth,
                  "levels of diffuse splitting");
  params_.add_int("diffuse_reflections", &s.diffuse_reflections, 1, 1024, "photons a split makes");
  params_.add_int("snowball_size", &s.snowball_size, 1, 64, "photons stored per hit");
  params_.add_int("light_distribution_type", &s.light_distribution_type, 0, 1,
                  "emission: 0 Saff-Kuijlaars, 1 random");
  params_.add_int("diffuse_light_distribution", &s.diffuse_light_distribution, 0, 1,
                  "bounces: 0 stratified, 1 random");
  params_.add_float("max_search_radius_rel", &s.max_search_radius_rel, 1e-6, 1.0,
                    "search radius / scene diagonal");
  params_.add_float("radius_heuristic_alpha", &s.radius_heuristic_alpha, 1e-6, 1.0,
                    "alpha of the radius heuristic");
  params_.add_float("slice_thickness_rel", &s.slice_thickness_rel, 1e-7, 1.0,
                    "sphere slice half-thickness / scene diagonal");
  params_.add_int("final_gathering_samples", &s.final_gathering_samples, 1, 65536,
                  "rays per final-gathered estimate");
  params_.add_int("stop_recursion_size", &s.stop_recursion_size, 1, 256,
                  "kd-tree leaf bucket size");
  params_.add_float("snowball_radius_rel", &s.snowball_radius_rel, 0.0, 1.0,
                    "snowball disc radius / scene diagonal");
  params_.add_bool("direction_test", &s.direction_test,
                   "photons from the other side of a surface do not count");
  params_.add_bool("roulette", &s.roulette,
                   "after the split levels, paths go on (Russian roulette)");
  params_.add_bool("exact_photon_map", &s.exact_photon_map,
                   "brute-force k nearest (the seed's Exact_photon_map)");
  params_.add_int("seed", &s.seed, 0, 1 << 30, "photon sample seed");
  params_.add_bool("keep_unchanged", &s.keep_unchanged,
                   "keep the kd-tree and estimates while the photons equal those they replace");
}

std::vector<TechniqueOption> VertexPhotonMapping::options() const {
  return {
      param_option("photons-from-light", "photons_from_light", "Photon paths per frame"),
      param_option("refine", "mesh_refinement", "Triangles added by mesh refinement"),
      param_option("accumulation-frames", "accumulation_frames", "Frames of photons kept"),
  };
}

std::vector<std::string> VertexPhotonMapping::still_defaults() const {
  return {"photons_from_light=2000"};
}

uint64_t VertexPhotonMapping::memory_estimate(const Scene& scene) const {
  const VertexSettings& s = settings_;
  // A path's split tree holds 1 + n + ... + n^depth photons for n = diffuse_reflections; each
  // photon of the last level may go on as a path ended by Russian roulette.
  const double n = double(std::max(s.diffuse_reflections, 1));
  double tree = 0.0, level = 1.0;
  for (int k = 0; k <= std::clamp(s.recursion_depth, 0, kMaxRecursionDepth); ++k) {
    tree += level;
    level *= n;
  }
  const double per_path = tree + (level / n) * expected_photon_deposits(scene, -1);
  const double slot = double(s.photons_from_light) * per_path;
  // Each photon is three vec3 (MapPhotons), held in the ring, in the map gathered from it and in
  // the kd-tree's copy in tree order; keep_unchanged holds one more slot (what a refill replaced).
  const double photon_copies =
      slot * double(s.accumulation_frames) * 3.0 + (s.keep_unchanged ? slot : 0.0);
  // Measured: peak resident memory grows by 343 bytes per triangle the refinement adds
  // (`/usr/bin/time -f %M bounce bench cornell -t vertex -W 64 -H 64 --refine N -n 1`, N = 0
  // and 2,000,000: 35 MB and 705 MB).
  constexpr double kRefinedTriangleBytes = 350.0;
  return saturating_bytes(photon_copies * 3.0 * sizeof(vec3) +
                          double(s.mesh_refinement) * kRefinedTriangleBytes);
}

void VertexPhotonMapping::prepare(const PrepareContext& c) {
  const VertexSettings& s = settings_;
  diagonal_ = std::max(c.scene.bounds.diagonal(), 1e-6f);
  // The tree can stay only if nothing it was built with changed but this frame's photons, which
  // are compared below; estimates also need their keys where they were.
  bool may_keep = s.keep_unchanged && started_ && !c.change.everything && !c.change.parameters &&
                  c.change.moved_meshes.empty();
  {
    ScopedStage stage(c.times, "prepare/refine");
    if (!started_ || c.change.everything || refined_with_ != s.mesh_refinement) {
      refined_.build(c.scene, uint32_t(s.mesh_refinement));
      refined_with_ = s.mesh_refinement;
      may_keep = false;
    } else if (!c.change.moved_meshes.empty()) {
      refined_.update(c.scene, c.change.moved_meshes);
    }
  }
  // The ring restarts when what it holds would be inconsistent: a new scene or parameters.
  // Moved lights and objects do not restart it: their old photons age out (seed §5.3.1).
  if (!started_ || c.change.everything || c.change.parameters ||
      ring().frames() != uint32_t(s.accumulation_frames)) {
    still_.reset(uint32_t(s.accumulation_frames));
    moving_.reset(uint32_t(s.accumulation_frames));
    moving_lights_.clear();
    frame_ = 0;
    still_traced_.assign(size_t(std::max(s.accumulation_frames, 1)), 0);
    still_fresh_since_ = 0;
  }
  started_ = true;
  // A light that moved (or changed) since the ring restarted keeps its photons apart from then
  // on (keep_unchanged): the tree of the others then stands while it alone moves, as the
  // flashlight does with the camera. The two trees are searched as one, so where a photon is
  // kept changes no estimate, only what has to be rebuilt. (A light added or removed starts the
  // flags again: they follow the lights' indices.)
  const std::vector<uint8_t> moving_before = moving_lights_;
  if (moving_lights_.size() != c.scene.lights.size() ||
      last_lights_.size() != c.scene.lights.size())
    moving_lights_.assign(c.scene.lights.size(), 0);
  else if (s.keep_unchanged)
    for (size_t l = 0; l < c.scene.lights.size(); ++l)
      if (!(c.scene.lights[l] == last_lights_[l])) moving_lights_[l] = 1;
  last_lights_ = c.scene.lights;
  // The still lights' photons of a slot traced before this frame are those a retrace would give
  // only if nothing they depend on changed since: geometry, materials, which lights move (a
  // still light that changes joins them), the settings.
  if (!may_keep || c.change.materials || moving_lights_ != moving_before)
    still_fresh_since_ = frame_ + 1;
  // At rest with accumulation, each frame's photons are a fresh set (the frames the pipeline
  // averages are then independent); otherwise the frame-coherent sets.
  rest_pass_ = c.continue_accumulation() ? rest_pass_ + 1 : 0;

  {
    ScopedStage stage(c.times, "prepare/photon trace");
    VertexPhotonSettings ps;
    ps.photons = uint32_t(s.photons_from_light);
    ps.frames = uint32_t(s.accumulation_frames);
    ps.slot = frame_;
    ps.saff_kuijlaars = s.light_distribution_type == 0;
    ps.stratified = s.diffuse_light_distribution == 0;
    ps.splits = uint32_t(s.diffuse_reflections);
    ps.recursion_depth = s.recursion_depth;
    ps.roulette = s.roulette;
    // Final gathering reads the light the gathered surfaces reflect: first hits included.
    ps.store_direct = s.store_direct_light || s.final_gathering;
    ps.snowball = s.snowball_size;
    ps.snowball_radius = s.snowball_radius_rel * diagonal_;
    ps.seed = uint32_t(s.seed);
    ps.every_triangle = !s.bsp_tree;
    ps.variant = rest_pass_;
    ps.moving = moving_lights_;
    // With the ring full, this frame's slot replaces photons the tree holds.
    may_keep = may_keep && ring().filled() == ring().frames();
    // Frame-coherent paths of the still lights, traced into this slot since the last change,
    // would retrace themselves: they are kept, and only the moving lights' paths traced.
    const uint32_t slot_index = frame_ % ring().frames();
    const uint32_t traced = still_traced_[slot_index];
    ps.reuse_still = may_keep && ps.variant == 0 && traced != 0 && traced >= still_fresh_since_;
    const size_t held = ring().slot(slot_index).size();
    MapPhotons& slot = ps.reuse_still ? still_.revisit(frame_) : still_.refill(frame_, may_keep);
    MapPhotons& moving_slot = moving_.refill(frame_, may_keep);
    const VertexPhotonStats stats =
        tracer_.trace(c.scene, c.scene_view, c.tracer, ps, slot, &moving_slot);
    reused_ = stats.reused;
    if (stats.emission_changed) still_fresh_since_ = frame_ + 1;
    // A fresh set at rest (variant) is not the slot's frame-coherent one.
    still_traced_[slot_index] = ps.variant == 0 ? frame_ + 1 : 0;
    c.counters.photon_paths += stats.paths;
    c.counters.photons_stored += stats.stored;
    c.counters.rays += stats.rays;
    if (stats.reused) {
      c.counters.photons_reused += held;
      c.counters.photons_stored += held;
    }
  }
  ++frame_;
  {
    ScopedStage stage(c.times, "prepare/kd-tree");
    // Frame-coherent photons retrace the same paths while nothing moved: then a ring holds what
    // it held, and the tree built on it stands.
    still_.update(uint32_t(s.stop_recursion_size), reused_);
    moving_.update(uint32_t(s.stop_recursion_size));
  }

  const EstimateSettings last = estimate_;
  EstimateSettings& e = estimate_;
  e.k = s.max_search_count;
  e.max_radius =
      s.max_search_radius > 0.0f ? s.max_search_radius : s.max_search_radius_rel * diagonal_;
  if (s.use_radius_heuristic && photon_count() > 0) {
    // Eq 3.7 with r_n the radius of the sphere around all photons.
    vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const MapPhotons* m : {&still_.photons(), &moving_.photons()})
      for (const vec3& p : m->position) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float rn = 0.5f * glm::length(hi - lo);
    e.max_radius =
        std::sqrt(float(e.k) * rn * rn / (s.radius_heuristic_alpha * float(photon_count())));
  }
  e.sphere_slice = s.use_sphere_slice;
  e.slice_half = s.slice_thickness_rel * diagonal_;
  e.direction_test = s.direction_test;
  e.exact = s.exact_photon_map;
  e.flux_scale = ring().filled() > 0 ? 1.0f / float(ring().filled()) : 0.0f;
  e.final_gather_rays = s.final_gathering ? s.final_gathering_samples : 0;
  e.final_gather_seed = hash_u32(uint32_t(s.seed) ^ rest_pass_);
  // Estimates made on the kept trees with the same settings stand (indirect reads known_).
  if (!(kept_tree() && kept_moving_tree() && e == last)) known_.clear();
}

namespace {

// Pixels x0 .. x1 - 1 of rows y0 .. y1 - 1, each starting from what the one before it in its row
// found (LocateHint): the same in the G-buffer pass's bands and in indirect().
void locate_block(const VertexPixelView& v, int x0, int y0, int x1, int y1) {
  for (int y = y0; y < y1; ++y) {
    LocateHint hint;
    for (int x = x0; x < x1; ++x) locate_pixel(v, v.g.index(x, y), hint);
  }
}

}  // namespace

VertexPixelView VertexPhotonMapping::pixel_buffers(const FrameContext& c) {
  const ConstGBufferView g = c.gbuffer.view();
  const size_t pixels = g.size();
  const RefinedMeshView mesh = refined_.view();
  const bool per_key = settings_.use_estimate_cache;
  // Estimates per key and side, or without the cache per refined triangle corner and side.
  const size_t slots = per_key ? size_t(mesh.key_count) * 2 : size_t(mesh.leaf_count) * 6;
  pixel_leaf_.resize(pixels);
  pixel_weights_.resize(pixels);
  pixel_side_.resize(pixels);
  needed_.assign(slots, 0);
  irradiance_.resize(slots);
  return {g,
          c.scene_view,
          mesh,
          pixel_leaf_.data(),
          pixel_weights_.data(),
          pixel_side_.data(),
          needed_.data(),
          per_key};
}

std::string VertexPhotonMapping::begin_gbuffer_bands(const FrameContext& c) {
  located_view_ = pixel_buffers(c);
  located_ = true;
  return "indirect/locate";
}

void VertexPhotonMapping::gbuffer_band(int x0, int y0, int x1, int y1) {
  locate_block(located_view_, x0, y0, x1, y1);
}

void VertexPhotonMapping::indirect(const FrameContext& c, Image& out) {
  const ConstGBufferView g = c.gbuffer.view();
  const size_t pixels = g.size();
  const bool per_key = settings_.use_estimate_cache;
  // (Located in the G-buffer pass only if that pass was over this G-buffer.)
  const bool located = located_ && located_view_.g.width == g.width &&
                       located_view_.g.height == g.height && located_view_.g.depth == g.depth;
  located_ = false;
  const VertexPixelView pv = located ? located_view_ : pixel_buffers(c);
  const RefinedMeshView mesh = pv.mesh;
  const size_t slots = needed_.size();
  if (!located) {
    ScopedStage stage(c.times, "indirect/locate");
    parallel_for(
        size_t(g.height), [&](size_t y) { locate_block(pv, 0, int(y), g.width, int(y) + 1); }, 1);
  }
  {
    ScopedStage stage(c.times, "indirect/estimate");
    // Estimates made since the tree was built stand while it does (keep_unchanged).
    if (known_.size() != slots) known_.assign(slots, 0);
    todo_.clear();
    for (size_t k = 0; k < slots; ++k)
      if (needed_[k] && !known_[k]) todo_.push_back(uint32_t(k));
    const VertexEstimateView ev{mesh,      photon_map(),       c.scene_view, c.tracer.view(),
                                estimate_, irradiance_.data(), per_key};
    parallel_for(
        todo_.size(), [&](size_t j) { estimate_slot(ev, todo_[j]); }, 16);
    for (const uint32_t k : todo_) known_[k] = 1;
    estimates_ = todo_.size();
  }
  ScopedStage stage(c.times, "indirect/interpolate");
  const ImageView image = out.view();
  parallel_for(
      pixels, [&](size_t i) { image.pixels[i] = interpolate_pixel(pv, irradiance_.data(), i); },
      1024);
}

}  // namespace bounce
