// BvhView: our own BVH as plain arrays, the handle kernels get (host and device alike). The
// arrays belong to a Bvh (bvh.h) on the host, or to device buffers holding copies of them.
//
// Layout, chosen for GPU traversal (Aila & Laine 2009): a node is two-wide and holds both
// children's boxes, so one 64-byte fetch lets a ray test both children and pick the nearer; leaf
// children point straight at their triangles, so a leaf costs no node fetch of its own.
// Triangles are stored in leaf order as their three vertices (not v0 and two edges: shared edges
// must give bit-identical vertices for the watertight test, which an edge added back would not).
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/math.h"
#include "bounce/trace/cutout_view.h"

namespace bounce {

struct alignas(16) BvhNode {
  // Child k's box: box[k][0..2] the low corner (x, y, z), box[k][3..5] the high corner.
  float box[2][6];
  // Child k: an inner child names its node (count[k] == 0); a leaf child names its first
  // triangle with kLeaf set and has count[k] triangles (an empty leaf has count 0 and an empty
  // box, which no ray enters).
  uint32_t child[2];
  uint32_t count[2];

  static constexpr uint32_t kLeaf = 0x80000000u;
};
static_assert(sizeof(BvhNode) == 64);

// A triangle in leaf order: its vertices, w unused (padding for 16-byte loads).
struct alignas(16) BvhTriangle {
  vec4 v0, v1, v2;
};
static_assert(sizeof(BvhTriangle) == 48);

// What a leaf triangle was in the scene: mesh index and triangle index within that mesh.
struct BvhTriangleId {
  uint32_t mesh = 0;
  uint32_t triangle = 0;
};

struct BvhView {
  const BvhNode* nodes = nullptr;  // nodes[0] is the root
  const BvhTriangle* triangles = nullptr;
  const BvhTriangleId* ids = nullptr;  // parallel to triangles
  uint32_t node_count = 0;             // 0 for a scene without triangles
  uint32_t triangle_count = 0;
  // Holes in alpha-masked materials that rays pass through; empty where the scene has none (and
  // in a view that does not carry them: Bvh::view(), the device's copy).
  CutoutView cutouts;
};
static_assert(std::is_trivially_copyable_v<BvhView>);

}  // namespace bounce
