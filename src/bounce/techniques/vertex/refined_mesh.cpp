#include "bounce/techniques/vertex/refined_mesh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <queue>
#include <tuple>
#include <unordered_map>

#include "bounce/core/parallel.h"

namespace bounce {

namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
}

struct PositionKey {
  uint32_t x, y, z;
  bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    return (size_t(k.x) * 0x9E3779B97F4A7C15ull) ^ (size_t(k.y) * 0xC2B2AE3D27D4EB4Full) ^
           (size_t(k.z) * 0x165667B19E3779F9ull);
  }
};
PositionKey position_key(vec3 p) {
  // +0.0 and -0.0 are one position.
  return {std::bit_cast<uint32_t>(p.x + 0.0f), std::bit_cast<uint32_t>(p.y + 0.0f),
          std::bit_cast<uint32_t>(p.z + 0.0f)};
}

// A triangle while refining: its points (winding kept), coarse triangle, the corners' coarse
// barycentrics and its node.
struct Work {
  uvec3 points;
  uint32_t coarse;
  vec2 bary[3];
  uint32_t node;
};

}  // namespace

void RefinedMesh::build(const Scene& scene, uint32_t added) {
  *this = RefinedMesh{};
  std::vector<Work> work;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    // Vertices at one position are one point (a seam in normals or UVs is no seam in space).
    std::unordered_map<PositionKey, uint32_t, PositionHash> points;
    std::vector<uint32_t> point_of_vertex(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const auto [it, fresh] =
          points.try_emplace(position_key(mesh.positions[v]), uint32_t(point_position_.size()));
      if (fresh) point_position_.push_back(mesh.positions[v]);
      point_of_vertex[v] = it->second;
    }
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const uvec3 tri = mesh.triangles[t];
      Work w;
      w.points = uvec3(point_of_vertex[tri.x], point_of_vertex[tri.y], point_of_vertex[tri.z]);
      w.coarse = uint32_t(work.size());
      w.bary[0] = vec2(0.0f);
      w.bary[1] = vec2(1.0f, 0.0f);
      w.bary[2] = vec2(0.0f, 1.0f);
      w.node = uint32_t(nodes_.size());
      nodes_.push_back(RefineNode{});
      work.push_back(w);
      mesh_of_coarse_.push_back(m);
    }
  }
  coarse_triangles_ = uint32_t(work.size());
  root_.resize(coarse_triangles_);
  for (uint32_t t = 0; t < coarse_triangles_; ++t) root_[t] = work[t].node;

  // Which triangles hold each edge.
  std::unordered_map<uint64_t, std::vector<uint32_t>> edges;
  edges.reserve(size_t(coarse_triangles_ + added) * 2);
  const auto add_edge = [&](uint32_t a, uint32_t b, uint32_t t) {
    edges[edge_key(a, b)].push_back(t);
  };
  const auto replace_edge = [&](uint32_t a, uint32_t b, uint32_t from, uint32_t to) {
    for (uint32_t& t : edges[edge_key(a, b)])
      if (t == from) t = to;
  };
  for (uint32_t t = 0; t < work.size(); ++t)
    for (int e = 0; e < 3; ++e) add_edge(work[t].points[e], work[t].points[(e + 1) % 3], t);

  // Longest edge first; an entry is stale once its triangle changed (its stamp moved on).
  using Entry =
      std::tuple<float, uint32_t, uint32_t>;  // length^2, -triangle (ties: lower id), stamp
  std::priority_queue<Entry> queue;
  std::vector<uint32_t> stamp(work.size(), 0);
  const auto longest = [&](const Work& w, int& edge) {
    float best = -1.0f;
    for (int e = 0; e < 3; ++e) {
      const vec3 d = point_position_[w.points[(e + 1) % 3]] - point_position_[w.points[e]];
      const float l2 = glm::dot(d, d);
      if (l2 > best) best = l2, edge = e;
    }
    return best;
  };
  const auto push = [&](uint32_t t) {
    int e;
    queue.emplace(longest(work[t], e), ~t, stamp[t]);
  };
  for (uint32_t t = 0; t < work.size(); ++t) push(t);

  const uint64_t target = uint64_t(coarse_triangles_) + added;
  while (work.size() < target && !queue.empty()) {
    const auto [l2, not_t, st] = queue.top();
    queue.pop();
    const uint32_t t = ~not_t;
    if (st != stamp[t] || !(l2 > 0.0f)) continue;
    int e;
    longest(work[t], e);
    const uint32_t a = work[t].points[e], b = work[t].points[(e + 1) % 3];
    const uint32_t m = uint32_t(point_position_.size());
    point_position_.push_back(0.5f * (point_position_[a] + point_position_[b]));
    const std::vector<uint32_t> sharing = edges[edge_key(a, b)];
    edges.erase(edge_key(a, b));
    for (const uint32_t x : sharing) {
      // x = (u, w, c) with u-w the split edge, in x's winding.
      const Work old = work[x];
      int i = 0;
      while (!((old.points[i] == a && old.points[(i + 1) % 3] == b) ||
               (old.points[i] == b && old.points[(i + 1) % 3] == a)))
        ++i;
      const int iw = (i + 1) % 3, ic = (i + 2) % 3;
      const uint32_t u = old.points[i], w = old.points[iw], c = old.points[ic];
      const vec2 bu = old.bary[i], bw = old.bary[iw], bc = old.bary[ic], bm = 0.5f * (bu + bw);
      const uint32_t x2 = uint32_t(work.size());
      Work first{uvec3(u, m, c), old.coarse, {bu, bm, bc}, uint32_t(nodes_.size())};
      Work second{uvec3(m, w, c), old.coarse, {bm, bw, bc}, uint32_t(nodes_.size() + 1)};
      nodes_.push_back(RefineNode{});
      nodes_.push_back(RefineNode{});
      RefineNode& split = nodes_[old.node];
      split.apex = bc;
      split.mid = bm;
      const bool u_positive = cross2(bm - bc, bu - bc) >= 0.0f;
      split.positive = u_positive ? first.node : second.node;
      split.negative = u_positive ? second.node : first.node;
      work[x] = first;
      work.push_back(second);
      stamp[x]++;
      stamp.push_back(0);
      replace_edge(w, c, x, x2);
      add_edge(u, m, x);
      add_edge(m, w, x2);
      add_edge(m, c, x);
      add_edge(m, c, x2);
      push(x);
      push(x2);
    }
  }

  // The refined triangles are the leaves; their nodes say so.
  const uint32_t leaves = uint32_t(work.size());
  leaf_points_.resize(leaves);
  leaf_map_.resize(leaves);
  leaf_coarse_.resize(leaves);
  leaf_keys_.resize(leaves);
  for (uint32_t t = 0; t < leaves; ++t) {
    const Work& w = work[t];
    nodes_[w.node].positive = nodes_[w.node].negative = t | kRefineLeaf;
    leaf_points_[t] = w.points;
    leaf_coarse_[t] = w.coarse;
    leaf_map_[t] = LeafMap::of(w.bary[0], w.bary[1], w.bary[2]);
  }
  // Links to a leaf node become links to the leaf itself.
  for (RefineNode& n : nodes_) {
    if (n.positive == n.negative) continue;
    const RefineNode& p = nodes_[n.positive];
    const RefineNode& q = nodes_[n.negative];
    if (p.positive == p.negative) n.positive = p.positive;
    if (q.positive == q.negative) n.negative = q.positive;
  }

  // Keys: a point and a normal (quantised), so that creases keep one estimate per side.
  struct KeyId {
    uint32_t point;
    int32_t nx, ny, nz;
    bool operator==(const KeyId&) const = default;
  };
  struct KeyHash {
    size_t operator()(const KeyId& k) const {
      return size_t(k.point) * 0x9E3779B97F4A7C15ull ^ size_t(uint32_t(k.nx)) * 0xC2B2AE3Dull ^
             size_t(uint32_t(k.ny)) * 0x27D4EB2Full ^ size_t(uint32_t(k.nz)) * 0x165667B1ull;
    }
  };
  std::unordered_map<KeyId, uint32_t, KeyHash> keys;
  for (uint32_t t = 0; t < leaves; ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t key = uint32_t(key_position_.size());
      key_position_.push_back(vec3(0.0f));
      key_normal_.push_back(vec3(0.0f));
      key_coarse_.push_back(leaf_coarse_[t]);
      key_bary_.push_back(work[t].bary[k]);
      key_mesh_.push_back(mesh_of_coarse_[leaf_coarse_[t]]);
      key_geometry(scene, key);
      const vec3 n = key_normal_[key];
      const KeyId id{leaf_points_[t][k], int32_t(std::lround(n.x * 1024.0f)),
                     int32_t(std::lround(n.y * 1024.0f)), int32_t(std::lround(n.z * 1024.0f))};
      const auto [it, fresh] = keys.try_emplace(id, key);
      if (!fresh) {
        key_position_.pop_back();
        key_normal_.pop_back();
        key_coarse_.pop_back();
        key_bary_.pop_back();
        key_mesh_.pop_back();
      }
      leaf_keys_[t][k] = it->second;
    }
  }
}

LeafMap LeafMap::of(vec2 c0, vec2 c1, vec2 c2) {
  // s = cross(b - c0, e2) / det and t = cross(e1, b - c0) / det, expanded in b (in double: the
  // determinant of a deep split is small).
  const double e1x = double(c1.x) - c0.x, e1y = double(c1.y) - c0.y;
  const double e2x = double(c2.x) - c0.x, e2y = double(c2.y) - c0.y;
  const double det = e1x * e2y - e1y * e2x;
  if (det == 0.0) return {};
  const double inv = 1.0 / det;
  LeafMap map;
  map.s = vec3(float(-(double(c0.x) * e2y - double(c0.y) * e2x) * inv), float(e2y * inv),
               float(-e2x * inv));
  map.t = vec3(float(-(e1x * double(c0.y) - e1y * double(c0.x)) * inv), float(-e1y * inv),
               float(e1x * inv));
  // A triangle too thin for floats: no point lies on it (as when the determinant is 0).
  return is_finite(map.s) && is_finite(map.t) ? map : LeafMap{};
}

void RefinedMesh::key_geometry(const Scene& scene, uint32_t key) {
  const uint32_t coarse = key_coarse_[key];
  const Mesh& mesh = scene.meshes[key_mesh_[key]];
  const uint32_t local = coarse - scene.triangle_offsets[key_mesh_[key]];
  const uvec3 tri = mesh.triangles[local];
  const vec2 b = key_bary_[key];
  const float b0 = 1.0f - b.x - b.y;
  key_position_[key] =
      b0 * mesh.positions[tri.x] + b.x * mesh.positions[tri.y] + b.y * mesh.positions[tri.z];
  const vec3 face = mesh.face_normal_area2(local);
  const float face_len = glm::length(face);
  vec3 n = face_len > 0.0f ? face / face_len : vec3(0.0f, 1.0f, 0.0f);
  if (!mesh.normals.empty()) {
    const vec3 s = b0 * mesh.normals[tri.x] + b.x * mesh.normals[tri.y] + b.y * mesh.normals[tri.z];
    const float len = glm::length(s);
    if (len > 0.0f) n = glm::dot(s, n) < 0.0f ? -s / len : s / len;
  }
  key_normal_[key] = n;
}

void RefinedMesh::update(const Scene& scene, const std::vector<uint32_t>& moved_meshes) {
  if (moved_meshes.empty()) return;
  std::vector<uint8_t> moved(scene.meshes.size(), 0);
  for (uint32_t m : moved_meshes)
    if (m < moved.size()) moved[m] = 1;
  parallel_for(
      key_position_.size(),
      [&](size_t k) {
        if (moved[key_mesh_[k]]) key_geometry(scene, uint32_t(k));
      },
      1024);
}

RefinedMeshView RefinedMesh::view() const {
  RefinedMeshView v;
  v.root = root_.data();
  v.nodes = nodes_.data();
  v.leaf_keys = leaf_keys_.data();
  v.leaf_map = leaf_map_.data();
  v.leaf_coarse = leaf_coarse_.data();
  v.key_position = key_position_.data();
  v.key_normal = key_normal_.data();
  v.leaf_count = uint32_t(leaf_coarse_.size());
  v.key_count = uint32_t(key_position_.size());
  return v;
}

}  // namespace bounce
