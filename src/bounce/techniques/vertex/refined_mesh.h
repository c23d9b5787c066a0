// The render mesh refined for per-vertex light (seed 004 §5.4.1, Fig 5.9; notes/seed-004.md
// §3.2): the triangle with the globally longest edge is split at that edge's midpoint, again and
// again (a priority queue), until the scene has the target number of triangles. Every triangle
// sharing the edge is split with it, so the refined mesh stays conforming (no T-junctions); as
// the split edge is the longest of the whole scene, it is also the longest of each neighbour.
// The tracing mesh (the Tracer's) stays coarse.
//
// Each coarse triangle keeps the tree of its splits, in its own barycentric coordinates, so a
// G-buffer pixel (coarse triangle id and barycentrics) finds its refined triangle by walking the
// tree: locate_refined. The light lives at "estimate points" (keys): refined vertices told apart
// by position and normal, shared by the refined triangles around them (the seed's estimate cache
// keyed by position, with the normal added as its notes advise).
#pragma once

#include <cstdint>
#include <type_traits>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/scene/scene.h"

namespace bounce {

inline constexpr uint32_t kRefineLeaf = 0x80000000u;

// A split of a triangle (A, u, w) at the midpoint M of edge u-w, in the coarse triangle's
// barycentric coordinates (weights of its vertices 1 and 2): the child on the positive side of
// the line A -> M first. A child with kRefineLeaf set is a refined triangle's index.
struct RefineNode {
  vec2 apex{0.0f};
  vec2 mid{0.0f};
  uint32_t positive = kRefineLeaf;
  uint32_t negative = kRefineLeaf;
};

// A refined triangle's corner weights (s, t) at coarse barycentrics b, as affine functions:
// s = s.x + s.y b.x + s.z b.y, and t alike. Made once when the mesh is refined, so that locating
// a pixel takes no division (the two divisions by the corners' determinant were a tenth of the
// locate stage). A degenerate triangle's map gives s = t = -1: no point lies on it.
struct LeafMap {
  vec3 s{-1.0f, 0.0f, 0.0f};
  vec3 t{-1.0f, 0.0f, 0.0f};

  // The map of the triangle with corners c0, c1, c2 (coarse barycentrics).
  static LeafMap of(vec2 c0, vec2 c1, vec2 c2);
};

struct RefinedMeshView {
  const uint32_t* root = nullptr;  // per coarse triangle (global id): its node
  const RefineNode* nodes = nullptr;
  const uvec3* leaf_keys = nullptr;   // per refined triangle: the keys of its corners
  const LeafMap* leaf_map = nullptr;  // per refined triangle: its weights at coarse barycentrics
  const uint32_t* leaf_coarse = nullptr;  // per refined triangle: its coarse triangle
  const vec3* key_position = nullptr;
  const vec3* key_normal = nullptr;  // unit, on the side the coarse triangle's winding faces
  uint32_t leaf_count = 0;
  uint32_t key_count = 0;
};
static_assert(std::is_trivially_copyable_v<RefinedMeshView>);

BOUNCE_HD inline float cross2(vec2 a, vec2 b) {
  return a.x * b.y - a.y * b.x;
}

// A point of a refined triangle: which one, and the weights of its three corners.
struct RefinedPoint {
  uint32_t leaf = 0;
  vec3 weights{1.0f, 0.0f, 0.0f};
};

// b's weights on refined triangle `leaf` (coarse barycentrics b), and whether b lies on it (the
// weights unclamped are all at least 0).
BOUNCE_HD inline bool weights_on_leaf(const RefinedMeshView& m, uint32_t leaf, vec2 b,
                                      vec3& weights) {
  const LeafMap& map = m.leaf_map[leaf];
  const float s_raw = map.s.x + map.s.y * b.x + map.s.z * b.y;
  const float t_raw = map.t.x + map.t.y * b.x + map.t.z * b.y;
  const float s = glm::clamp(s_raw, 0.0f, 1.0f);
  const float t = glm::clamp(t_raw, 0.0f, 1.0f - s);
  weights = vec3(1.0f - s - t, s, t);
  return (s_raw >= 0.0f) & (t_raw >= 0.0f) & (s_raw + t_raw <= 1.0f);
}

// The refined triangle of coarse triangle `coarse` at its barycentrics b, and b's weights there.
// `hint`, a refined triangle a neighbouring pixel found (or kNoHint), is taken without a descent
// of the tree where b lies on it: neighbouring pixels mostly share one, and the descent's
// branches go either way.
inline constexpr uint32_t kNoHint = 0xFFFFFFFFu;
BOUNCE_HD inline RefinedPoint locate_refined(const RefinedMeshView& m, uint32_t coarse, vec2 b,
                                             uint32_t hint = kNoHint) {
  RefinedPoint p;
  if (hint != kNoHint && m.leaf_coarse[hint] == coarse && weights_on_leaf(m, hint, b, p.weights)) {
    p.leaf = hint;
    return p;
  }
  uint32_t node = m.root[coarse];
  for (;;) {
    const RefineNode& n = m.nodes[node];
    // A leaf is a node whose children are the same refined triangle (a coarse triangle never
    // split), or a child link that carries the leaf flag.
    if (n.positive == n.negative) {
      node = n.positive;
      break;
    }
    const uint32_t next = cross2(n.mid - n.apex, b - n.apex) >= 0.0f ? n.positive : n.negative;
    if (next & kRefineLeaf) {
      node = next;
      break;
    }
    node = next;
  }
  p.leaf = node & ~kRefineLeaf;
  weights_on_leaf(m, p.leaf, b, p.weights);
  return p;
}

class RefinedMesh {
 public:
  // Refines every mesh of the scene until it has at least coarse + `added` triangles (the
  // seed's mesh_refinement counted splits, each adding one; a conforming split adds one per
  // triangle on the edge).
  void build(const Scene& scene, uint32_t added);
  // Moves the keys of meshes whose vertices moved (the refinement is kept: rigid and small
  // motions leave it fit).
  void update(const Scene& scene, const std::vector<uint32_t>& moved_meshes);

  RefinedMeshView view() const;
  uint32_t coarse_triangles() const { return coarse_triangles_; }
  uint32_t triangles() const { return uint32_t(leaf_coarse_.size()); }
  uint32_t keys() const { return uint32_t(key_position_.size()); }
  // The refined triangles' corners as indices of keys (a mesh of keys), for tests and export.
  const std::vector<uvec3>& leaf_keys() const { return leaf_keys_; }
  const std::vector<vec3>& key_positions() const { return key_position_; }
  // The refined points (one per position within a mesh) of each refined triangle's corners:
  // what conformity is about (shared positions, whatever their normals).
  const std::vector<uvec3>& leaf_points() const { return leaf_points_; }
  const std::vector<vec3>& point_positions() const { return point_position_; }

 private:
  void key_geometry(const Scene& scene, uint32_t key);

  uint32_t coarse_triangles_ = 0;
  std::vector<uint32_t> root_;
  std::vector<RefineNode> nodes_;
  std::vector<uvec3> leaf_keys_;
  std::vector<uvec3> leaf_points_;
  std::vector<LeafMap> leaf_map_;
  std::vector<uint32_t> leaf_coarse_;
  std::vector<vec3> point_position_;
  std::vector<vec3> key_position_;
  std::vector<vec3> key_normal_;
  std::vector<uint32_t> key_coarse_;  // a coarse triangle the key lies on, and where
  std::vector<vec2> key_bary_;
  std::vector<uint32_t> key_mesh_;
  std::vector<uint32_t> mesh_of_coarse_;
};

}  // namespace bounce
