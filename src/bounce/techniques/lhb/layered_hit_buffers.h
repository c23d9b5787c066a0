// Layered hit buffers (seed 001): the scene deep-rasterized along a set of directions, the
// discrete visibility field the `lhb` technique gathers through. This is the owning container:
// it builds the static slab once, rebuilds the moving meshes' slab each frame they move, and
// hands out the plain LhbView that kernels (lhb_query.h) read.
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
#include "bounce/techniques/lhb/lhb_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

struct LhbSettings {
  int size = 128;               // texels per side of each direction's buffer (seed default)
  int layers = 16;              // elements per texel, static slab (seed default)
  int dynamic_layers = 16;      // elements per texel, moving meshes' slab
  bool cull_back_faces = true;  // keep only faces a ray along the direction meets from the front

  static constexpr int kMaxSize = 4096;
  static constexpr int kMaxLayers = 254;  // counts saturate at 255
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
  double dynamic_build_ms = 0.0;  // the last rebuild of the moving meshes
  uint64_t static_builds = 0, dynamic_builds = 0;
};

class LayeredHitBuffers {
 public:
  // Builds every buffer: one per unit direction. Meshes listed in dynamic_meshes (and meshes the
  // scene's animation drives) go to the moving slab, the rest to the static one. Throws Error on
  // settings out of range or a direction that is not a unit vector.
  void build(const Scene& scene, std::span<const vec3> directions, const LhbSettings& settings,
             std::span<const uint32_t> dynamic_meshes = {});

  // Follows a frame's change (seed 001 section 6): nothing for camera, light or material
  // changes; moving meshes rebuild the moving slab; a mesh that moves for the first time joins
  // the moving meshes (the static slab is rebuilt once without it); geometry leaving the
  // buffers' region, or change.everything, rebuilds everything. Returns whether anything was
  // rebuilt.
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

  void build_static(const Scene& scene);
  void build_dynamic(const Scene& scene);
  void allocate(Slab& slab, int layers) const;
  void rasterize(const Scene& scene, std::span<const uint32_t> meshes, Slab& slab) const;
  bool inside_region(const Bounds& b) const;

  LhbSettings settings_;
  std::vector<vec3> directions_;
  std::vector<LhbFrame> frames_;
  Bounds region_;  // the world box every buffer covers
  std::vector<uint32_t> static_meshes_, dynamic_meshes_;
  std::vector<uint32_t> triangle_offsets_;  // the scene's, for global id -> (mesh, triangle)
  Slab static_, dynamic_;
  double static_build_ms_ = 0.0, dynamic_build_ms_ = 0.0;
  uint64_t static_builds_ = 0, dynamic_builds_ = 0;
};

}  // namespace bounce
