#include "bounce/techniques/lhb/layered_hit_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/enumerable_thread_specific.h>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/timer.h"
#include "bounce/techniques/lhb/deep_raster_kernels.h"
#include "bounce/techniques/lhb/lhb_query.h"
#include "bounce/trace/cutouts.h"

namespace bounce {
namespace {

// Room around the scene's bounds, as a fraction of its diagonal, so that small moves of the
// moving meshes stay inside the buffers without a full rebuild.
constexpr float kRegionMargin = 0.05f;

// Buffer frame for direction d over the world box `region`: u, v across d (Duff et al.'s basis),
// and the texel scales that fit the box's projection into size x size texels.
LhbFrame frame_for(vec3 d, const Bounds& region, int size) {
  const Basis basis = Basis::from_normal(d);
  float lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const vec3 p((corner & 1) ? region.hi.x : region.lo.x, (corner & 2) ? region.hi.y : region.lo.y,
                 (corner & 4) ? region.hi.z : region.lo.z);
    lo_u = std::min(lo_u, glm::dot(p, basis.t));
    hi_u = std::max(hi_u, glm::dot(p, basis.t));
    lo_v = std::min(lo_v, glm::dot(p, basis.b));
    hi_v = std::max(hi_v, glm::dot(p, basis.b));
  }
  // A flat region (a single quad seen edge-on) still gets a non-zero extent.
  const float floor_extent = 1e-6f * (1.0f + region.diagonal());
  const float extent_u = std::max(hi_u - lo_u, floor_extent);
  const float extent_v = std::max(hi_v - lo_v, floor_extent);
  return {basis.t, basis.b, d, lo_u, lo_v, float(size) / extent_u, float(size) / extent_v};
}

}  // namespace

void LayeredHitBuffers::build(const Scene& scene, std::span<const vec3> directions,
                              const LhbSettings& settings,
                              std::span<const uint32_t> dynamic_meshes) {
  if (settings.size < 1 || settings.size > LhbSettings::kMaxSize)
    fail("layered hit buffers: size {} is outside [1, {}]", settings.size, LhbSettings::kMaxSize);
  for (int layers : {settings.layers, settings.dynamic_layers})
    if (layers < 1 || layers > LhbSettings::kMaxLayers)
      fail("layered hit buffers: {} layers is outside [1, {}]", layers, LhbSettings::kMaxLayers);
  if (directions.empty()) fail("layered hit buffers: no directions");
  for (size_t i = 0; i < directions.size(); ++i)
    if (!is_finite(directions[i]) || std::abs(glm::length(directions[i]) - 1.0f) > 1e-3f)
      fail("layered hit buffers: direction {} ({}, {}, {}) is not a unit vector", i,
           directions[i].x, directions[i].y, directions[i].z);
  for (uint32_t m : dynamic_meshes)
    if (m >= scene.meshes.size())
      fail("layered hit buffers: moving mesh {} does not exist ({} meshes in {})", m,
           scene.meshes.size(), scene.source);

  settings_ = settings;
  directions_.assign(directions.begin(), directions.end());
  dynamic_meshes_.assign(dynamic_meshes.begin(), dynamic_meshes.end());
  for (const AnimatedMesh& a : scene.animation.meshes) dynamic_meshes_.push_back(a.mesh);
  std::sort(dynamic_meshes_.begin(), dynamic_meshes_.end());
  dynamic_meshes_.erase(std::unique(dynamic_meshes_.begin(), dynamic_meshes_.end()),
                        dynamic_meshes_.end());
  static_builds_ = dynamic_builds_ = 0;
  build_static(scene);
  build_dynamic(scene);
}

void LayeredHitBuffers::build_static(const Scene& scene) {
  const Stopwatch watch;
  region_ = scene.bounds;
  if (region_.empty()) region_.extend(vec3(0.0f));
  const vec3 margin(kRegionMargin * region_.diagonal() + 1e-4f);
  region_.lo -= margin;
  region_.hi += margin;
  frames_.resize(directions_.size());
  for (size_t d = 0; d < directions_.size(); ++d)
    frames_[d] = frame_for(directions_[d], region_, settings_.size);
  triangle_offsets_ = scene.triangle_offsets;

  static_meshes_.clear();
  for (uint32_t m = 0; m < scene.meshes.size(); ++m)
    if (!std::binary_search(dynamic_meshes_.begin(), dynamic_meshes_.end(), m))
      static_meshes_.push_back(m);
  allocate(static_, settings_.layers);
  rasterize(scene, static_meshes_, static_);
  static_build_ms_ = watch.elapsed_ms();
  ++static_builds_;
}

void LayeredHitBuffers::build_dynamic(const Scene& scene) {
  const Stopwatch watch;
  if (dynamic_meshes_.empty()) {
    dynamic_ = Slab{};
    return;
  }
  if (!dynamic_.elements) allocate(dynamic_, settings_.dynamic_layers);
  triangle_offsets_ = scene.triangle_offsets;
  rasterize(scene, dynamic_meshes_, dynamic_);
  dynamic_build_ms_ = watch.elapsed_ms();
  ++dynamic_builds_;
}

void LayeredHitBuffers::allocate(Slab& slab, int layers) const {
  slab.layers = layers;
  slab.texels = frames_.size() * size_t(settings_.size) * size_t(settings_.size);
  // Elements are written before they are read (counts say how many), so they start uninitialised.
  slab.elements.reset(new LhbElement[slab.texels * size_t(layers)]);
  slab.counts.reset(new uint8_t[slab.texels]);
}

void LayeredHitBuffers::rasterize(const Scene& scene, std::span<const uint32_t> meshes,
                                  Slab& slab) const {
  const size_t per_direction = size_t(settings_.size) * size_t(settings_.size);
  std::vector<MeshView> views;
  std::vector<uint32_t> first_prim;
  uint32_t most_vertices = 0;  // the projection scratch each task needs
  Cutouts cutouts;             // alpha-masked holes leave no element
  cutouts.build(scene);        // empty for a scene without cut-outs
  const CutoutView cutout_view = cutouts.view();
  slab.triangles = 0;
  for (uint32_t m : meshes) {
    views.push_back(scene.meshes[m].view());
    most_vertices = std::max(most_vertices, views.back().vertex_count);
    first_prim.push_back(scene.triangle_offsets[m]);
    slab.triangles += scene.meshes[m].triangles.size();
  }
  // Each thread's projected vertices, reused across its directions.
  tbb::enumerable_thread_specific<std::vector<LhbProjected>> scratch;
  // One task per direction: it owns that buffer's texels, so insertion needs no atomics and the
  // lists do not depend on the thread count. 320 directions keep every core busy.
  std::vector<LhbRasterStats> per_direction_stats(frames_.size());
  std::vector<uint64_t> overflow(frames_.size(), 0);
  parallel_for(
      frames_.size(),
      [&](size_t d) {
        const LhbSlabOut out{slab.elements.get() + d * per_direction * size_t(slab.layers),
                             slab.counts.get() + d * per_direction, slab.layers};
        std::memset(out.counts, 0, per_direction);
        LhbRasterStats stats;
        std::vector<LhbProjected>& projected = scratch.local();
        if (projected.size() < most_vertices) projected.resize(most_vertices);
        for (size_t k = 0; k < views.size(); ++k)
          lhb_raster_mesh(frames_[d], settings_.size, views[k], meshes[k], first_prim[k],
                          settings_.cull_back_faces, cutout_view, projected.data(), out, stats);
        uint64_t full = 0;
        for (size_t t = 0; t < per_direction; ++t) full += out.counts[t] > slab.layers;
        per_direction_stats[d] = stats;
        overflow[d] = full;
      },
      1);
  slab.kept = slab.dropped = slab.overflow_texels = 0;
  for (size_t d = 0; d < frames_.size(); ++d) {
    slab.kept += per_direction_stats[d].arrived - per_direction_stats[d].dropped;
    slab.dropped += per_direction_stats[d].dropped;
    slab.overflow_texels += overflow[d];
  }
}

bool LayeredHitBuffers::inside_region(const Bounds& b) const {
  return b.empty() || (glm::all(glm::greaterThanEqual(b.lo, region_.lo)) &&
                       glm::all(glm::lessThanEqual(b.hi, region_.hi)));
}

bool LayeredHitBuffers::update(const Scene& scene, const SceneChange& change) {
  if (frames_.empty()) fail("layered hit buffers: update before build");
  const bool counts_changed = scene.triangle_offsets != triangle_offsets_;
  if (change.everything || counts_changed || !inside_region(scene.bounds)) {
    for (uint32_t m : change.moved_meshes) dynamic_meshes_.push_back(m);
    std::sort(dynamic_meshes_.begin(), dynamic_meshes_.end());
    dynamic_meshes_.erase(std::unique(dynamic_meshes_.begin(), dynamic_meshes_.end()),
                          dynamic_meshes_.end());
    dynamic_meshes_.erase(std::remove_if(dynamic_meshes_.begin(), dynamic_meshes_.end(),
                                         [&](uint32_t m) { return m >= scene.meshes.size(); }),
                          dynamic_meshes_.end());
    dynamic_ = Slab{};
    build_static(scene);
    build_dynamic(scene);
    return true;
  }
  if (change.moved_meshes.empty()) return false;
  bool newcomer = false;
  for (uint32_t m : change.moved_meshes)
    if (!std::binary_search(dynamic_meshes_.begin(), dynamic_meshes_.end(), m)) {
      dynamic_meshes_.insert(std::upper_bound(dynamic_meshes_.begin(), dynamic_meshes_.end(), m),
                             m);
      newcomer = true;
    }
  // A mesh that starts moving leaves the static slab once; afterwards only its own slab is redone.
  if (newcomer) build_static(scene);
  build_dynamic(scene);
  return true;
}

LhbView LayeredHitBuffers::view() const {
  LhbView v;
  v.frames = frames_.data();
  v.direction_count = int(frames_.size());
  v.size = settings_.size;
  v.static_slab = static_.view();
  if (dynamic_.elements) v.dynamic_slab = dynamic_.view();
  return v;
}

LhbStats LayeredHitBuffers::stats() const {
  LhbStats s;
  s.memory_bytes = static_.bytes() + dynamic_.bytes() + frames_.size() * sizeof(LhbFrame);
  s.directions = int(frames_.size());
  s.static_triangles = static_.triangles;
  s.dynamic_triangles = dynamic_.triangles;
  s.static_elements = static_.kept;
  s.dynamic_elements = dynamic_.kept;
  s.dropped_elements = static_.dropped + dynamic_.dropped;
  s.overflow_texels = static_.overflow_texels + dynamic_.overflow_texels;
  s.static_build_ms = static_build_ms_;
  s.dynamic_build_ms = dynamic_build_ms_;
  s.static_builds = static_builds_;
  s.dynamic_builds = dynamic_builds_;
  return s;
}

float LayeredHitBuffers::texel_size(int direction) const {
  const LhbFrame& f = frames_[size_t(direction)];
  return std::max(1.0f / f.scale_u, 1.0f / f.scale_v);
}

Hit LayeredHitBuffers::closest_hit(const Ray& ray, int direction, vec2 jitter) const {
  if (direction < 0 || direction >= int(frames_.size()))
    fail("layered hit buffers: direction {} is outside [0, {})", direction, frames_.size());
  const LhbHit h = lhb_closest(view(), direction, ray.origin, ray.tmin, jitter);
  Hit hit;
  if (!h.valid() || !(h.t <= ray.tmax)) return hit;
  const auto next = std::upper_bound(triangle_offsets_.begin(), triangle_offsets_.end(), h.prim);
  hit.mesh = uint32_t(next - triangle_offsets_.begin()) - 1;
  hit.triangle = h.prim - triangle_offsets_[hit.mesh];
  hit.t = h.t;
  return hit;
}

}  // namespace bounce
