// Bvh: our own bounding volume hierarchy over every triangle of a scene, built on the CPU and
// traversed on either side (bvh_view.h holds the layout, bvh_traversal.h the traversal). The CPU
// tracer on it is BvhTracer (bvh_tracer.h); the CUDA backend copies its arrays to the device.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bounce/scene/scene.h"
#include "bounce/trace/bvh_view.h"

namespace bounce {

class Bvh {
 public:
  // Leaves hold at most this many triangles; the SAH picks smaller ones where they pay.
  static constexpr uint32_t kMaxLeafSize = 4;

  Bvh() = default;
  explicit Bvh(const Scene& scene) { build(scene); }

  // Binned-SAH build over all triangles of all meshes (meshes without triangles add nothing).
  void build(const Scene& scene);
  // Catches up with meshes whose vertices moved: when each keeps its vertex and triangle counts,
  // their triangles are rewritten and every box is refitted bottom-up (the tree keeps its shape);
  // otherwise the whole tree is rebuilt. Returns true for a refit, false for a rebuild.
  bool refit(const Scene& scene, std::span<const uint32_t> moved_meshes);

  // Plain pointers into this Bvh's arrays: valid until the next build or refit.
  BvhView view() const;
  // The arrays a device copy needs: nodes (the root first), triangles in leaf order, and what
  // each triangle was in the scene.
  const std::vector<BvhNode>& nodes() const { return nodes_; }
  const std::vector<BvhTriangle>& triangles() const { return triangles_; }
  const std::vector<BvhTriangleId>& ids() const { return ids_; }

  size_t memory_bytes() const;
  double build_ms() const { return build_ms_; }  // the last build
  double refit_ms() const { return refit_ms_; }  // the last refit
  // Levels of inner nodes on the longest path from the root (the root alone is 1).
  uint32_t depth() const { return depth_; }

 private:
  std::vector<BvhNode> nodes_;
  std::vector<BvhTriangle> triangles_;
  std::vector<BvhTriangleId> ids_;
  std::vector<size_t> vertex_counts_, triangle_counts_;  // per mesh, as built
  double build_ms_ = 0.0;
  double refit_ms_ = 0.0;
  uint32_t depth_ = 0;
};

}  // namespace bounce
