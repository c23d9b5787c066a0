// Binned-SAH build (Wald 2007) of the two-wide BVH in bvh_view.h, and its refit.
//
// Node slots are given out deterministically, so the tree is the same whatever the thread count:
// a subtree over n triangles has at most n - 1 inner nodes, so the node over [begin, end) takes
// slot s, its left subtree (n_left triangles) the slots from s + 1 and its right subtree those
// from s + n_left. Subtrees then build in parallel without sharing a counter, and a final pass
// numbers the used slots depth first (parents before children, which refit relies on).
#include "bounce/trace/bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <limits>

#include "bounce/core/error.h"
#include "bounce/core/timer.h"
#include "bounce/trace/bvh_traversal.h"

namespace bounce {

namespace {

constexpr int kBins = 16;
// Beyond this depth splits are at the object median, which halves the count each level: the
// tree's depth stays within the traversal's stack whatever the geometry.
constexpr uint32_t kSahDepth = 32;
// Subtrees above this many triangles build their two halves in parallel.
constexpr uint32_t kParallelCount = 4096;
// SAH costs of a traversal step and of a triangle test (relative).
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.0f;

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Box {
  vec3 lo{kInf};
  vec3 hi{-kInf};

  void grow(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  void grow(vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x; }
  float half_area() const {
    if (empty()) return 0.0f;
    const vec3 d = hi - lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }
};

// A triangle while building: its box, its centre, and its index in scene order.
struct Prim {
  Box box;
  vec3 centre{0.0f};
  uint32_t index = 0;
};

// A finished child: a leaf (triangles [first, first + count)) or an inner node's slot.
struct ChildRef {
  uint32_t child = 0;
  uint32_t count = 0;
  Box box;
};

void set_child(BvhNode& node, int k, const ChildRef& ref) {
  node.child[k] = ref.child;
  node.count[k] = ref.count;
  for (int a = 0; a < 3; ++a) {
    node.box[k][a] = ref.box.lo[a];
    node.box[k][a + 3] = ref.box.hi[a];
  }
}

Box child_box(const BvhNode& node, int k) {
  Box b;
  b.lo = vec3(node.box[k][0], node.box[k][1], node.box[k][2]);
  b.hi = vec3(node.box[k][3], node.box[k][4], node.box[k][5]);
  return b;
}

class Builder {
 public:
  Builder(std::vector<Prim>& prims, std::vector<BvhNode>& slots) : prims_(prims), slots_(slots) {}

  ChildRef build(uint32_t begin, uint32_t end, uint32_t slot, uint32_t depth) {
    const uint32_t n = end - begin;
    Box box, centres;
    for (uint32_t i = begin; i < end; ++i) {
      box.grow(prims_[i].box);
      centres.grow(prims_[i].centre);
    }
    const ChildRef leaf{BvhNode::kLeaf | begin, n, box};
    if (n == 1) return leaf;

    uint32_t mid = begin;
    if (depth < kSahDepth) {
      const Split split = best_split(begin, end, centres);
      const float leaf_cost = kTriangleCost * float(n);
      const float split_cost =
          kTraversalCost + kTriangleCost * split.cost / std::max(box.half_area(), 1e-30f);
      if (n <= Bvh::kMaxLeafSize && (split.axis < 0 || leaf_cost <= split_cost)) return leaf;
      if (split.axis >= 0) mid = partition(begin, end, centres, split);
    } else if (n <= Bvh::kMaxLeafSize) {
      return leaf;
    }
    if (mid == begin || mid == end) mid = median(begin, end, centres);

    ChildRef left, right;
    const auto build_left = [&] { left = build(begin, mid, slot + 1, depth + 1); };
    const auto build_right = [&] { right = build(mid, end, slot + (mid - begin), depth + 1); };
    if (n > kParallelCount) {
      tbb::parallel_invoke(build_left, build_right);
    } else {
      build_left();
      build_right();
    }
    BvhNode& node = slots_[slot];
    set_child(node, 0, left);
    set_child(node, 1, right);
    return {slot, 0, box};
  }

 private:
  struct Split {
    int axis = -1;      // -1: no plane separates the centres
    int plane = 0;      // bins [0, plane) go left
    float cost = kInf;  // sum over both sides of half area x triangle count
  };

  static int bin_of(float c, float lo, float scale) {
    return std::clamp(int((c - lo) * scale), 0, kBins - 1);
  }
  static float bin_scale(const Box& centres, int axis) {
    const float extent = centres.hi[axis] - centres.lo[axis];
    return extent > 0.0f ? float(kBins) * (1.0f - 1e-6f) / extent : 0.0f;
  }

  Split best_split(uint32_t begin, uint32_t end, const Box& centres) const {
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      const float scale = bin_scale(centres, axis);
      if (scale == 0.0f) continue;
      Box bins[kBins];
      uint32_t counts[kBins] = {};
      for (uint32_t i = begin; i < end; ++i) {
        const int b = bin_of(prims_[i].centre[axis], centres.lo[axis], scale);
        bins[b].grow(prims_[i].box);
        ++counts[b];
      }
      // Sweep from the right for the right sides' costs, then from the left.
      float right_cost[kBins];
      Box acc;
      uint32_t count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.grow(bins[b]);
        count += counts[b];
        right_cost[b] = count ? acc.half_area() * float(count) : kInf;
      }
      acc = Box{};
      count = 0;
      for (int plane = 1; plane < kBins; ++plane) {
        acc.grow(bins[plane - 1]);
        count += counts[plane - 1];
        if (count == 0) continue;
        const float cost = acc.half_area() * float(count) + right_cost[plane];
        if (cost < best.cost) best = {axis, plane, cost};
      }
    }
    return best;
  }

  uint32_t partition(uint32_t begin, uint32_t end, const Box& centres, const Split& split) {
    const float scale = bin_scale(centres, split.axis);
    const float lo = centres.lo[split.axis];
    const auto it = std::partition(
        prims_.begin() + begin, prims_.begin() + end,
        [&](const Prim& p) { return bin_of(p.centre[split.axis], lo, scale) < split.plane; });
    return uint32_t(it - prims_.begin());
  }

  // Halves the range along the centres' longest axis (ties broken by scene order, so the result
  // does not depend on the sort's whims).
  uint32_t median(uint32_t begin, uint32_t end, const Box& centres) {
    const vec3 extent = centres.hi - centres.lo;
    const int axis =
        extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                     [axis](const Prim& a, const Prim& b) {
                       return a.centre[axis] < b.centre[axis] ||
                              (a.centre[axis] == b.centre[axis] && a.index < b.index);
                     });
    return mid;
  }

  std::vector<Prim>& prims_;
  std::vector<BvhNode>& slots_;
};

BvhTriangle make_triangle(const Mesh& mesh, uint32_t t) {
  const uvec3 i = mesh.triangles[t];
  return {vec4(mesh.positions[i.x], 0.0f), vec4(mesh.positions[i.y], 0.0f),
          vec4(mesh.positions[i.z], 0.0f)};
}

Box triangle_box(const BvhTriangle& tri) {
  Box b;
  b.grow(vec3(tri.v0));
  b.grow(vec3(tri.v1));
  b.grow(vec3(tri.v2));
  return b;
}

}  // namespace

void Bvh::build(const Scene& scene) {
  Stopwatch watch;
  nodes_.clear();
  triangles_.clear();
  ids_.clear();
  depth_ = 0;
  vertex_counts_.assign(scene.meshes.size(), 0);
  triangle_counts_.assign(scene.meshes.size(), 0);

  // Every triangle in scene order.
  std::vector<BvhTriangleId> scene_ids;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    vertex_counts_[m] = mesh.positions.size();
    triangle_counts_[m] = mesh.triangles.size();
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) scene_ids.push_back({m, t});
  }
  if (scene_ids.size() >= BvhNode::kLeaf)
    fail("{}: {} triangles are more than the BVH can index", scene.source, scene_ids.size());
  const uint32_t n = uint32_t(scene_ids.size());
  if (n == 0) {
    build_ms_ = watch.elapsed_ms();
    return;
  }

  std::vector<Prim> prims(n);
  tbb::parallel_for(uint32_t(0), n, [&](uint32_t i) {
    const BvhTriangleId id = scene_ids[i];
    prims[i].box = triangle_box(make_triangle(scene.meshes[id.mesh], id.triangle));
    prims[i].centre = 0.5f * (prims[i].box.lo + prims[i].box.hi);
    prims[i].index = i;
  });

  std::vector<BvhNode> slots(std::max(n - 1, 1u));
  Builder builder(prims, slots);
  const ChildRef root = builder.build(0, n, 0, 1);
  if (root.count > 0) {
    // The whole scene is one leaf: the root holds it beside an empty leaf no ray enters.
    set_child(slots[0], 0, root);
    set_child(slots[0], 1, ChildRef{BvhNode::kLeaf, 0, Box{}});
  }

  // Number the used slots depth first, the left child first.
  std::vector<uint32_t> order;  // slots in their new order
  std::vector<uint32_t> renumber(slots.size(), 0);
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 1u}};  // slot, depth
  while (!stack.empty()) {
    const auto [slot, depth] = stack.back();
    stack.pop_back();
    renumber[slot] = uint32_t(order.size());
    order.push_back(slot);
    depth_ = std::max(depth_, depth);
    for (int k = 1; k >= 0; --k)
      if (!(slots[slot].child[k] & BvhNode::kLeaf))
        stack.push_back({slots[slot].child[k], depth + 1});
  }
  if (depth_ > uint32_t(bvh_detail::kStackSize))
    fail("{}: the BVH is {} levels deep, more than its traversal's stack", scene.source, depth_);
  nodes_.resize(order.size());
  for (uint32_t i = 0; i < order.size(); ++i) {
    nodes_[i] = slots[order[i]];
    for (int k = 0; k < 2; ++k)
      if (!(nodes_[i].child[k] & BvhNode::kLeaf)) nodes_[i].child[k] = renumber[nodes_[i].child[k]];
  }

  triangles_.resize(n);
  ids_.resize(n);
  tbb::parallel_for(uint32_t(0), n, [&](uint32_t i) {
    ids_[i] = scene_ids[prims[i].index];
    triangles_[i] = make_triangle(scene.meshes[ids_[i].mesh], ids_[i].triangle);
  });
  build_ms_ = watch.elapsed_ms();
}

bool Bvh::refit(const Scene& scene, std::span<const uint32_t> moved_meshes) {
  Stopwatch watch;
  if (scene.meshes.size() != vertex_counts_.size()) {
    build(scene);
    return false;
  }
  std::vector<uint8_t> moved(scene.meshes.size(), 0);
  for (uint32_t m : moved_meshes) {
    const Mesh& mesh = scene.meshes.at(m);
    if (mesh.positions.size() != vertex_counts_[m] ||
        mesh.triangles.size() != triangle_counts_[m]) {
      build(scene);  // the topology changed: the tree's shape cannot follow
      return false;
    }
    moved[m] = 1;
  }
  if (nodes_.empty() || moved_meshes.empty()) return true;

  tbb::parallel_for(size_t(0), triangles_.size(), [&](size_t i) {
    if (moved[ids_[i].mesh])
      triangles_[i] = make_triangle(scene.meshes[ids_[i].mesh], ids_[i].triangle);
  });
  // Children come after their parents, so a backward sweep sees every child's box first.
  for (size_t i = nodes_.size(); i-- > 0;) {
    BvhNode& node = nodes_[i];
    for (int k = 0; k < 2; ++k) {
      Box box;
      if (node.child[k] & BvhNode::kLeaf) {
        const uint32_t first = node.child[k] & ~BvhNode::kLeaf;
        for (uint32_t t = first; t < first + node.count[k]; ++t)
          box.grow(triangle_box(triangles_[t]));
      } else {
        const BvhNode& child = nodes_[node.child[k]];
        box = child_box(child, 0);
        box.grow(child_box(child, 1));
      }
      set_child(node, k, ChildRef{node.child[k], node.count[k], box});
    }
  }
  refit_ms_ = watch.elapsed_ms();
  return true;
}

BvhView Bvh::view() const {
  return {nodes_.data(),           triangles_.data(),           ids_.data(),
          uint32_t(nodes_.size()), uint32_t(triangles_.size()), CutoutView{}};
}

size_t Bvh::memory_bytes() const {
  return nodes_.size() * sizeof(BvhNode) + triangles_.size() * sizeof(BvhTriangle) +
         ids_.size() * sizeof(BvhTriangleId);
}

}  // namespace bounce
