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
  if (settings.max_instances < 0 || settings.max_instances > LhbSettings::kMaxInstances)
    fail("layered hit buffers: {} instances is outside [0, {}]", settings.max_instances,
         LhbSettings::kMaxInstances);
  if (directions.size() > 65535)
    fail("layered hit buffers: {} directions (at most 65535)", directions.size());
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
  // The nearest-direction lookup that maps a turned instance's directions.
  direction_lookup_ = DirectionSet::from_directions(directions_, "hit buffer directions");
  dynamic_meshes_.assign(dynamic_meshes.begin(), dynamic_meshes.end());
  for (const AnimatedMesh& a : scene.animation.meshes) dynamic_meshes_.push_back(a.mesh);
  std::sort(dynamic_meshes_.begin(), dynamic_meshes_.end());
  dynamic_meshes_.erase(std::unique(dynamic_meshes_.begin(), dynamic_meshes_.end()),
                        dynamic_meshes_.end());
  static_builds_ = dynamic_builds_ = 0;
  instance_captures_ = instance_reposes_ = 0;
  rebuild_all(scene);
}

void LayeredHitBuffers::rebuild_all(const Scene& scene) {
  instances_.clear();
  dynamic_ = Slab{};
  build_static(scene);
  assign_moving(scene);
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
  allocate(static_, settings_.layers, slab_texels());
  rasterize(scene, static_meshes_, frames_, settings_.size, static_);
  static_build_ms_ = watch.elapsed_ms();
  ++static_builds_;
}

void LayeredHitBuffers::build_dynamic(const Scene& scene) {
  if (slab_meshes_.empty()) {
    dynamic_ = Slab{};
    return;
  }
  if (!dynamic_.elements) allocate(dynamic_, settings_.dynamic_layers, slab_texels());
  triangle_offsets_ = scene.triangle_offsets;
  rasterize(scene, slab_meshes_, frames_, settings_.size, dynamic_);
  ++dynamic_builds_;
}

size_t LayeredHitBuffers::slab_texels() const {
  return frames_.size() * size_t(settings_.size) * size_t(settings_.size);
}

size_t LayeredHitBuffers::texels_left(const Instance* except) const {
  size_t used = 0;
  for (const Instance& inst : instances_)
    if (&inst != except) used += inst.slab.texels;
  return slab_texels() > used ? slab_texels() - used : 0;
}

std::vector<LayeredHitBuffers::Instance>::iterator LayeredHitBuffers::find_instance(uint32_t mesh) {
  return std::find_if(instances_.begin(), instances_.end(),
                      [mesh](const Instance& inst) { return inst.mesh == mesh; });
}

void LayeredHitBuffers::refresh_views() {
  instance_views_.clear();
  for (const Instance& inst : instances_) instance_views_.push_back(inst.view());
}

void LayeredHitBuffers::assign_moving(const Scene& scene) {
  // The candidates, largest first: they cost the most to rasterize again.
  std::vector<uint32_t> wanted;
  for (uint32_t m : dynamic_meshes_)
    if (scene.meshes[m].triangles.size() >= size_t(std::max(settings_.instance_min_triangles, 1)))
      wanted.push_back(m);
  std::stable_sort(wanted.begin(), wanted.end(), [&](uint32_t a, uint32_t b) {
    return scene.meshes[a].triangles.size() > scene.meshes[b].triangles.size();
  });
  if (wanted.size() > size_t(settings_.max_instances))
    wanted.resize(size_t(settings_.max_instances));
  std::erase_if(instances_, [&](const Instance& inst) {
    return std::find(wanted.begin(), wanted.end(), inst.mesh) == wanted.end();
  });
  for (uint32_t m : wanted) {
    if (find_instance(m) != instances_.end()) continue;
    Instance inst;
    inst.mesh = m;
    if (capture(scene, inst, texels_left())) instances_.push_back(std::move(inst));
  }
  slab_meshes_.clear();
  for (uint32_t m : dynamic_meshes_)
    if (find_instance(m) == instances_.end()) slab_meshes_.push_back(m);
  refresh_views();
}

bool LayeredHitBuffers::capture(const Scene& scene, Instance& inst, size_t texel_budget) {
  const Mesh& mesh = scene.meshes[inst.mesh];
  const std::optional<AffineAnchors> anchors = AffineAnchors::choose(mesh.positions);
  if (!anchors) return false;  // a line or a point: it covers no texel, the slab takes it
  Bounds box;
  for (const vec3& p : mesh.positions) box.extend(p);
  // Texels as large as the scene buffers' along each direction; one size for all directions:
  // the diameter of the mesh's bounding sphere, plus a texel of margin.
  const vec3 centre = box.centre();
  float radius2 = 0.0f;  // of the sphere about the box's centre that holds every vertex
  for (const vec3& p : mesh.positions)
    radius2 = std::max(radius2, glm::dot(p - centre, p - centre));
  const float radius = std::sqrt(radius2);
  float widest = 0.0f;  // the sphere's diameter in texels, over all directions
  for (const LhbFrame& f : frames_)
    widest = std::max(widest, 2.0f * radius * std::max(f.scale_u, f.scale_v));
  const int size = std::clamp(int(std::ceil(widest)) + 1, 1, settings_.size);
  // Coarser texels when the mesh is wider than the scene's buffers allow.
  const float shrink = std::min(1.0f, float(size) / std::max(widest, 1e-30f));
  const size_t texels = frames_.size() * size_t(size) * size_t(size);
  if (texels > texel_budget) return false;
  inst.size = size;
  inst.frames.resize(frames_.size());
  for (size_t j = 0; j < frames_.size(); ++j) {
    LhbFrame f = frames_[j];
    f.scale_u *= shrink;
    f.scale_v *= shrink;
    f.u0 = glm::dot(centre, f.u) - 0.5f * float(size) / f.scale_u;
    f.v0 = glm::dot(centre, f.v) - 0.5f * float(size) / f.scale_v;
    inst.frames[j] = f;
  }
  // The box a ray enters before it can meet the mesh, two texels wider: a list holds depths at
  // texel centres, which on a sloped surface lie up to a texel's slope nearer than the surface
  // under the ray, and the query only takes elements beyond where it enters.
  float texel = 0.0f;
  for (const LhbFrame& f : inst.frames)
    texel = std::max({texel, 1.0f / f.scale_u, 1.0f / f.scale_v});
  const vec3 pad(2.0f * texel + 1e-3f * box.diagonal() + 1e-6f);
  inst.box_lo = box.lo - pad;
  inst.box_hi = box.hi + pad;
  inst.rest = mesh.positions;
  inst.anchors = *anchors;
  inst.pose = Affine{};
  if (!inst.slab.elements || inst.slab.texels != texels)
    allocate(inst.slab, settings_.dynamic_layers, texels);
  const uint32_t one[1] = {inst.mesh};
  rasterize(scene, one, inst.frames, size, inst.slab);
  map_directions(inst);
  ++instance_captures_;
  return true;
}

void LayeredHitBuffers::map_directions(Instance& inst) const {
  const mat3 inverse = glm::inverse(inst.pose.linear);
  const DirectionSetView lookup = direction_lookup_.view();
  inst.direction_of.resize(directions_.size());
  for (size_t k = 0; k < directions_.size(); ++k)
    inst.direction_of[k] = uint16_t(lookup.nearest(glm::normalize(inverse * directions_[k])));
}

bool LayeredHitBuffers::repose(const Scene& scene, Instance& inst) {
  const std::vector<vec3>& now = scene.meshes[inst.mesh].positions;
  const std::optional<Affine> map = fit_affine(inst.anchors, inst.rest, now);
  // Kept while the map neither mirrors (back faces would swap) nor stretches the texels by more
  // than 2x (singular values within [0.5, 2], bounded through the columns and the inverse's).
  bool keep = map && glm::determinant(map->linear) > 0.0f;
  if (keep) {
    const mat3 inverse = glm::inverse(map->linear);
    for (int c = 0; c < 3 && keep; ++c)
      keep = glm::length(map->linear[c]) <= 2.0f && glm::length(inverse[c]) <= 2.0f;
  }
  if (!keep) {
    // Not an affine move (or too far a stretch): capture the mesh again in its new pose, with
    // texels sized for it, if it still fits beside the other instances.
    return capture(scene, inst, texels_left(&inst));
  }
  const bool turned = map->linear != inst.pose.linear;
  inst.pose = *map;
  if (turned) map_directions(inst);
  ++instance_reposes_;
  return true;
}

void LayeredHitBuffers::allocate(Slab& slab, int layers, size_t texels) const {
  slab.layers = layers;
  slab.texels = texels;
  // Elements are written before they are read (counts say how many), so they start uninitialised.
  slab.elements.reset(new LhbElement[slab.texels * size_t(layers)]);
  slab.counts.reset(new uint8_t[slab.texels]);
}

void LayeredHitBuffers::rasterize(const Scene& scene, std::span<const uint32_t> meshes,
                                  std::span<const LhbFrame> frames, int size, Slab& slab) const {
  const size_t per_direction = size_t(size) * size_t(size);
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
  std::vector<LhbRasterStats> per_direction_stats(frames.size());
  std::vector<uint64_t> overflow(frames.size(), 0);
  parallel_for(
      frames.size(),
      [&](size_t d) {
        const LhbSlabOut out{slab.elements.get() + d * per_direction * size_t(slab.layers),
                             slab.counts.get() + d * per_direction, slab.layers};
        std::memset(out.counts, 0, per_direction);
        LhbRasterStats stats;
        std::vector<LhbProjected>& projected = scratch.local();
        if (projected.size() < most_vertices) projected.resize(most_vertices);
        for (size_t k = 0; k < views.size(); ++k)
          lhb_raster_mesh(frames[d], size, views[k], meshes[k], first_prim[k],
                          settings_.cull_back_faces, cutout_view, projected.data(), out, stats);
        uint64_t full = 0;
        for (size_t t = 0; t < per_direction; ++t) full += out.counts[t] > slab.layers;
        per_direction_stats[d] = stats;
        overflow[d] = full;
      },
      1);
  slab.kept = slab.dropped = slab.overflow_texels = 0;
  for (size_t d = 0; d < frames.size(); ++d) {
    slab.kept += per_direction_stats[d].arrived - per_direction_stats[d].dropped;
    slab.dropped += per_direction_stats[d].dropped;
    slab.overflow_texels += overflow[d];
  }
}

bool LayeredHitBuffers::slab_inside_region(const Scene& scene) const {
  for (uint32_t m : slab_meshes_)
    for (const vec3& p : scene.meshes[m].positions)
      if (!glm::all(glm::greaterThanEqual(p, region_.lo)) ||
          !glm::all(glm::lessThanEqual(p, region_.hi)))
        return false;
  return true;
}

bool LayeredHitBuffers::update(const Scene& scene, const SceneChange& change) {
  if (frames_.empty()) fail("layered hit buffers: update before build");
  const bool counts_changed = scene.triangle_offsets != triangle_offsets_;
  const auto join = [&](uint32_t m) {
    if (m >= scene.meshes.size() ||
        std::binary_search(dynamic_meshes_.begin(), dynamic_meshes_.end(), m))
      return false;
    dynamic_meshes_.insert(std::upper_bound(dynamic_meshes_.begin(), dynamic_meshes_.end(), m), m);
    return true;
  };
  if (change.everything || counts_changed) {
    std::erase_if(dynamic_meshes_, [&](uint32_t m) { return m >= scene.meshes.size(); });
    for (uint32_t m : change.moved_meshes) join(m);
    rebuild_all(scene);
    return true;
  }
  if (change.moved_meshes.empty()) return false;
  const Stopwatch watch;
  bool newcomer = false;
  for (uint32_t m : change.moved_meshes) newcomer |= join(m);
  if (newcomer) {
    // A mesh that starts moving leaves the static slab once; afterwards only it is redone.
    build_static(scene);
    assign_moving(scene);
  }
  bool slab_moved = newcomer;
  bool dropped = false;
  for (uint32_t m : change.moved_meshes) {
    const auto inst = find_instance(m);
    if (inst == instances_.end()) {
      slab_moved = true;
    } else if (!repose(scene, *inst)) {
      // Neither re-posed nor captured again: the mesh joins the slab.
      instances_.erase(inst);
      dropped = true;
    }
  }
  if (dropped) assign_moving(scene);
  slab_moved |= dropped;
  // Instances may go anywhere; the slab covers the static buffers' region only.
  if (!slab_inside_region(scene)) {
    rebuild_all(scene);
    return true;
  }
  if (slab_moved) build_dynamic(scene);
  refresh_views();
  dynamic_build_ms_ = watch.elapsed_ms();
  return true;
}

LhbInstanceView LayeredHitBuffers::Instance::view() const {
  LhbInstanceView v;
  v.linear = pose.linear;
  v.inverse = glm::inverse(pose.linear);
  v.offset = pose.offset;
  v.box_lo = box_lo;
  v.box_hi = box_hi;
  v.frames = frames.data();
  v.direction_of = direction_of.data();
  v.size = size;
  v.slab = slab.view();
  return v;
}

std::vector<uint32_t> LayeredHitBuffers::instance_meshes() const {
  std::vector<uint32_t> meshes;
  for (const Instance& inst : instances_) meshes.push_back(inst.mesh);
  return meshes;
}

LhbView LayeredHitBuffers::view() const {
  LhbView v;
  v.frames = frames_.data();
  v.direction_count = int(frames_.size());
  v.size = settings_.size;
  v.static_slab = static_.view();
  if (dynamic_.elements) v.dynamic_slab = dynamic_.view();
  v.instances = instance_views_.data();
  v.instance_count = int(instance_views_.size());
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
  for (const Instance& inst : instances_) {
    s.memory_bytes += inst.slab.bytes() + inst.frames.size() * sizeof(LhbFrame) +
                      inst.direction_of.size() * sizeof(uint16_t) + inst.rest.size() * sizeof(vec3);
    s.instance_triangles += inst.slab.triangles;
    s.instance_texels += inst.slab.texels;
    s.dynamic_elements += inst.slab.kept;
    s.dropped_elements += inst.slab.dropped;
    s.overflow_texels += inst.slab.overflow_texels;
  }
  s.instances = int(instances_.size());
  s.static_build_ms = static_build_ms_;
  s.dynamic_build_ms = dynamic_build_ms_;
  s.static_builds = static_builds_;
  s.dynamic_builds = dynamic_builds_;
  s.instance_captures = instance_captures_;
  s.instance_reposes = instance_reposes_;
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
