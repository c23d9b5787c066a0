// Layered hit buffers (seed 001): the scene deep-rasterized along a set of directions, the
// discrete visibility field the `lhb` technique gathers through. This is the owning container:
// it builds the static slab once; large moving meshes get buffers of their own (instances),
// built once and re-posed each frame while their motion is affine; the small ones share a slab
// rasterized again each frame they move. It hands out the plain LhbView that kernels
// (lhb_query.h) read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/scene/bounds.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"
#include "bounce/techniques/lhb/affine_pose.h"
#include "bounce/techniques/lhb/direction_sets.h"
#include "bounce/techniques/lhb/lhb_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

struct LhbSettings {
  int size = 128;               // texels per side of each direction's buffer (seed default)
  int layers = 16;              // elements per texel, static slab (seed default)
  int dynamic_layers = 16;      // elements per texel, moving meshes' slab
  bool cull_back_faces = true;  // keep only faces a ray along the direction meets from the front
  // Moving meshes of at least instance_min_triangles triangles, the largest max_instances of
  // them, become instances: buffers over the mesh alone (texels as large as the scene's), built
  // once and re-posed by the mesh's affine motion, rebuilt only when it deforms, mirrors or
  // changes size by more than 2x. Instances together take at most one slab's texels. The rest
  // share the moving slab, rasterized again each frame they move (the seed's way): cheap for
  // few triangles, while every instance costs each query a lookup. 0: no instances.
  int max_instances = 8;
  int instance_min_triangles = 256;

  static constexpr int kMaxSize = 4096;
  static constexpr int kMaxLayers = 254;  // counts saturate at 255
  static constexpr int kMaxInstances = 64;
};

struct LhbStats {
  size_t memory_bytes = 0;  // element slabs, counts and frames
  int directions = 0;
  uint64_t static_triangles = 0, dynamic_triangles = 0;
  uint64_t static_elements = 0, dynamic_elements = 0;  // elements kept
  // Overflow: elements that found their texel full (dropped: the texel keeps its nearest
  // `layers`), and how many texels that happened in.
  uint64_t dropped_elements = 0;
  uint64_t overflow_texels = 0;
  double static_build_ms = 0.0;   // the last static build
  double dynamic_build_ms = 0.0;  // the moving meshes' work of the last frame they moved
  uint64_t static_builds = 0, dynamic_builds = 0;  // dynamic: rasterizations of the moving slab
  int instances = 0;                               // moving meshes with buffers of their own
  uint64_t instance_triangles = 0;
  uint64_t instance_texels = 0;    // over all directions: size^2 x directions per instance
  uint64_t instance_captures = 0;  // instance buffers rasterized (first pose, or re-captured)
  uint64_t instance_reposes = 0;   // frames an instance moved by a transform alone
};

class LayeredHitBuffers {
 public:
  // Builds every buffer: one per unit direction. Meshes listed in dynamic_meshes (and meshes the
  // scene's animation drives) go to the moving slab, the rest to the static one. Throws Error on
  // settings out of range or a direction that is not a unit vector.
  void build(const Scene& scene, std::span<const vec3> directions, const LhbSettings& settings,
             std::span<const uint32_t> dynamic_meshes = {});

  // Follows a frame's change (seed 001 section 6): nothing for camera, light or material
  // changes; a moving instance takes its new transform (or is captured again when its motion is
  // not affine); other moving meshes rebuild the moving slab; a mesh that moves for the first
  // time joins the moving meshes (the static slab is rebuilt once without it); slab geometry
  // leaving the buffers' region (instances may go anywhere), or change.everything, rebuilds
  // everything. Returns whether anything was rebuilt or re-posed.
  bool update(const Scene& scene, const SceneChange& change);

  LhbView view() const;
  LhbStats stats() const;
  size_t memory_bytes() const { return stats().memory_bytes; }
  const LhbSettings& settings() const { return settings_; }
  int direction_count() const { return int(frames_.size()); }
  const LhbFrame& frame(int direction) const { return frames_[size_t(direction)]; }
  // The larger side of one texel of buffer `direction`, in world units.
  float texel_size(int direction) const;
  const std::vector<uint32_t>& dynamic_meshes() const { return dynamic_meshes_; }
  // The moving meshes that are instances, in the view's order.
  std::vector<uint32_t> instance_meshes() const;

  // The closest hit of `ray` through buffer `direction` (ray.direction is taken to be that
  // direction; the caller snaps it): Embree's question answered by the buffers, with mesh and
  // triangle named and t the distance along the buffer's direction (no barycentrics). tmax is
  // honoured. `jitter` shifts the projected origin, in texels (the cone approximation).
  Hit closest_hit(const Ray& ray, int direction, vec2 jitter = vec2(0.0f)) const;

 private:
  struct Slab {
    std::unique_ptr<LhbElement[]> elements;
    std::unique_ptr<uint8_t[]> counts;
    size_t texels = 0;
    int layers = 0;
    uint64_t triangles = 0, kept = 0, dropped = 0, overflow_texels = 0;
    LhbSlabView view() const { return {elements.get(), counts.get(), layers}; }
    size_t bytes() const { return texels * (size_t(layers) * sizeof(LhbElement) + 1); }
  };

  // A moving mesh with buffers of its own, over its bounding box in the pose it was captured
  // in; `pose` carries that pose to the mesh's current one.
  struct Instance {
    uint32_t mesh = 0;
    std::vector<vec3> rest;  // the captured positions
    AffineAnchors anchors;
    Affine pose;
    vec3 box_lo{0.0f}, box_hi{0.0f};  // in the captured pose, slightly widened
    std::vector<LhbFrame> frames;
    std::vector<uint16_t> direction_of;  // world direction -> the instance's nearest
    int size = 0;
    Slab slab;
    LhbInstanceView view() const;
  };

  void build_static(const Scene& scene);
  void build_dynamic(const Scene& scene);
  void rebuild_all(const Scene& scene);
  // Chooses which moving meshes are instances (capturing the new ones) and which share the slab.
  void assign_moving(const Scene& scene);
  bool capture(const Scene& scene, Instance& inst, size_t texel_budget);
  // Follows the mesh to its current pose: by a transform when its motion is affine, else by
  // capturing it again; false when neither works (it no longer fits the budget, or it collapsed
  // to a line), and the caller moves it to the slab.
  bool repose(const Scene& scene, Instance& inst);
  void map_directions(Instance& inst) const;
  void allocate(Slab& slab, int layers, size_t texels) const;
  void rasterize(const Scene& scene, std::span<const uint32_t> meshes,
                 std::span<const LhbFrame> frames, int size, Slab& slab) const;
  bool slab_inside_region(const Scene& scene) const;
  size_t slab_texels() const;  // texels of one slab: directions x size^2
  // What one slab's texels leave to instances, not counting `except`'s own.
  size_t texels_left(const Instance* except = nullptr) const;
  std::vector<Instance>::iterator find_instance(uint32_t mesh);
  void refresh_views();  // instance_views_ from instances_

  LhbSettings settings_;
  std::vector<vec3> directions_;
  DirectionSet direction_lookup_;  // the same directions, for the nearest-direction lookup
  std::vector<LhbFrame> frames_;
  Bounds region_;  // the world box every buffer covers
  std::vector<uint32_t> static_meshes_, dynamic_meshes_;  // dynamic: every moving mesh
  std::vector<uint32_t> slab_meshes_;                     // the moving ones in the slab
  std::vector<uint32_t> triangle_offsets_;  // the scene's, for global id -> (mesh, triangle)
  Slab static_, dynamic_;
  std::vector<Instance> instances_;
  std::vector<LhbInstanceView> instance_views_;  // what view() hands out, kept in step
  double static_build_ms_ = 0.0, dynamic_build_ms_ = 0.0;
  uint64_t static_builds_ = 0, dynamic_builds_ = 0;
  uint64_t instance_captures_ = 0, instance_reposes_ = 0;
};

}  // namespace bounce
