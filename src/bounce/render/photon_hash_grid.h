// A uniform hashed grid for fixed-radius gathers over photon positions: the second
// density-estimation path of the `tiled` technique (the first bins photons into screen tiles).
//
// Cells are 2 * radius wide, so a gather of that radius touches the 2x2x2 block of cells nearest
// the query point. Cells are hashed into a power-of-two table and the points are counting-sorted
// by slot; a slot may hold several cells (hash collisions), which the distance test filters.
//
// The query lives in PhotonHashGridView, plain data over raw pointers with no allocation,
// exceptions or virtual calls, so the same code can run inside a CUDA kernel later.
#pragma once

#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// True when p is strictly within radius sqrt(radius2) of x. The one distance test of the grid, so
// callers that need the same set (brute-force cross-checks) can use exactly the same arithmetic.
BOUNCE_HD inline bool within_radius(vec3 p, vec3 x, float radius2) {
  const vec3 d = p - x;
  return d.x * d.x + d.y * d.y + d.z * d.z < radius2;
}

// Read-only view of a built grid; trivially copyable, so a kernel can take it by value.
struct PhotonHashGridView {
  // Cell coordinates are clamped to +-2^21: far enough for any scene at photon-radius scale, and
  // small enough that float rounding of x +- r moves a query's cell range by at most one cell
  // (see cell_range), so a gather never needs more than 3 cells per axis. Points beyond share the
  // boundary cells: still found, only slower.
  static constexpr float kCellLimit = 2097152.0f;
  static constexpr int kMaxCellsPerAxis = 3;

  const uint32_t* cell_start = nullptr;  // table_size + 1 offsets into index / point
  const uint32_t* index = nullptr;       // input index of each point, sorted by slot
  const vec3* point = nullptr;           // positions in the same (sorted) order
  uint32_t table_mask = 0;               // table_size - 1; table_size is a power of two
  uint32_t count = 0;                    // points binned (non-finite ones are skipped)
  float radius = 0.0f;                   // build radius
  float inv_cell = 0.0f;                 // 1 / (2 * radius)

  // Integer cell coordinate (floor) of a coordinate already scaled by inv_cell. Written out by
  // hand because GCC turns std::fmin/fmax and, after a clamp, std::floor into library calls. NaN
  // fails both comparisons and maps to a bound, so the int conversion is always defined; within
  // the clamp it truncates exactly and the correction makes it a floor.
  BOUNCE_HD static int32_t cell_coord(float scaled) {
    scaled = scaled > -kCellLimit ? scaled : -kCellLimit;
    scaled = scaled < kCellLimit ? scaled : kCellLimit;
    const int32_t truncated = int32_t(scaled);
    return truncated - int32_t(scaled < float(truncated));
  }
  BOUNCE_HD ivec3 cell(vec3 p) const {
    return {cell_coord(p.x * inv_cell), cell_coord(p.y * inv_cell), cell_coord(p.z * inv_cell)};
  }
  // Large-prime XOR hash (Teschner et al. 2003) followed by a full-avalanche finaliser (Wellons'
  // lowbias32), since the raw XOR hash has poor low bits and we keep only the low bits.
  BOUNCE_HD uint32_t slot(ivec3 c) const {
    uint32_t h = uint32_t(c.x) * 73856093u ^ uint32_t(c.y) * 19349663u ^ uint32_t(c.z) * 83492791u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h & table_mask;
  }

  // Cells [lo, hi] that can hold a point within `r` of x. They come from the rounded bounds
  // x - r and x + r: float rounding is monotonic, so a point p with |p - x| < r per axis (which
  // within_radius implies) has lo <= cell(p) <= hi exactly, whatever the rounding. For r <= radius
  // the range is 1 or 2 cells per axis (3 only when rounding straddles two boundaries).
  BOUNCE_HD void cell_range(vec3 x, float r, ivec3& lo, ivec3& hi) const {
    lo = cell(x - vec3(r));
    hi = cell(x + vec3(r));
    // Only a query radius above the build radius can exceed 3 cells; stay in bounds regardless.
    hi = glm::min(hi, lo + ivec3(kMaxCellsPerAxis - 1));
  }

  // Calls visit(index) for every point strictly within `r` (<= radius) of x, each once: cells in
  // z, y, x order, slots visited once even when two cells share one, index order within a slot.
  template <typename Visit>
  BOUNCE_HD void for_each_within(vec3 x, float r, Visit&& visit) const {
    assert(!(r > radius));  // NaN and r <= 0 are fine: they find nothing
    if (count == 0 || !(r > 0.0f) || !is_finite(x)) return;
    const float r2 = r * r;
    ivec3 lo, hi;
    cell_range(x, r, lo, hi);
    uint32_t seen[kMaxCellsPerAxis * kMaxCellsPerAxis * kMaxCellsPerAxis];
    int seen_count = 0;
    for (int cz = lo.z; cz <= hi.z; ++cz) {
      for (int cy = lo.y; cy <= hi.y; ++cy) {
        for (int cx = lo.x; cx <= hi.x; ++cx) {
          const uint32_t s = slot(ivec3(cx, cy, cz));
          const uint32_t begin = cell_start[s], end = cell_start[s + 1];
          if (begin == end) continue;
          bool repeated = false;
          for (int k = 0; k < seen_count; ++k) repeated |= seen[k] == s;
          if (repeated) continue;
          seen[seen_count++] = s;
          for (uint32_t k = begin; k < end; ++k)
            if (within_radius(point[k], x, r2)) visit(index[k]);
        }
      }
    }
  }
};

class PhotonHashGrid {
 public:
  // Bins points (photon positions) for gathers of radius `radius` (> 0, finite): cell size
  // 2 * radius. Counting sort by cell hash, deterministic: the same points give the same arrays
  // whatever the thread count, and within a slot points keep their index order. Non-finite points
  // are skipped (never visited). Throws Error for a bad radius or more than 2^30 points.
  // Buffers are kept between builds, so rebuilding every frame does not reallocate.
  void build(std::span<const vec3> points, float radius);

  // Calls visit(index) for every point within `radius` of x (distance < radius), each once, in a
  // deterministic order (cell by cell in a fixed order, index order within a cell). `radius`
  // must be <= the build radius. `index` is the point's index in the span given to build.
  template <typename Visit>
  void for_each_within(vec3 x, float radius, Visit&& visit) const {
    view().for_each_within(x, radius, visit);
  }

  float radius() const { return radius_; }
  // Points binned: the build's input less its non-finite points.
  size_t size() const { return points_.size(); }
  size_t table_size() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }
  // Made on demand from the owned arrays, so copies and moves of the grid need no fix-up.
  PhotonHashGridView view() const {
    PhotonHashGridView v;
    v.cell_start = cell_start_.data();
    v.index = indices_.data();
    v.point = points_.data();
    v.table_mask = uint32_t(table_size() - 1);
    v.count = uint32_t(points_.size());
    v.radius = radius_;
    v.inv_cell = inv_cell_;
    return v;
  }

  // The sorted arrays, for tests and for uploading to another device.
  std::span<const uint32_t> cell_start() const { return cell_start_; }
  std::span<const uint32_t> indices() const { return indices_; }
  std::span<const vec3> sorted_points() const { return points_; }

 private:
  std::vector<uint32_t> cell_start_;
  std::vector<uint32_t> indices_;
  std::vector<vec3> points_;
  std::vector<uint32_t> slots_;  // scratch: slot of each input point
  float radius_ = 0.0f;
  float inv_cell_ = 0.0f;
};

}  // namespace bounce
