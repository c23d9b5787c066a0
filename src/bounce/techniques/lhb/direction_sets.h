// The discrete directions of the layered hit buffers (seed 001, section 3): subdivided Platonic
// solids (octahedron, icosahedron, tetrahedron), Halton points and a spherical UV grid, each with
// a constant-time "nearest direction" lookup. The seed's directional map is a lat-long texture
// that stores one index per texel (approximate near region borders); ours is an octahedral grid
// whose cells list every direction that can be nearest to some point of the cell, so the lookup
// is exact and its work bounded by the longest list.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/core/octahedral.h"

namespace bounce {

enum class DirectionKind : int {
  kIcosahedron = 0,  // 20 * 4^level face centres (the seed's default: level 2, 320)
  kOctahedron = 1,   // 8 * 4^level
  kTetrahedron = 2,  // 4 * 4^level
  kHalton = 3,       // any count: 2D Halton points mapped to the sphere by equal area
  kUvGrid = 4,       // 4 L^2: 2L latitude bands x 2L longitude sectors, cell centres
};
inline constexpr int kDirectionKindCount = 5;

// Plain data of a direction set for kernels: the directions and the lookup grid.
struct DirectionSetView {
  const vec3* directions = nullptr;
  int count = 0;
  int grid = 0;                               // cells per side of the octahedral grid
  const uint32_t* cell_start = nullptr;       // grid*grid + 1 offsets into cell_candidates
  const uint16_t* cell_candidates = nullptr;  // direction indices, ascending per cell

  // Index of the direction with the largest dot product with `unit` (the first on ties, as a
  // brute-force scan in index order would give).
  BOUNCE_HD int nearest(vec3 unit) const {
    const vec2 e = oct_encode(unit);
    const int cx = cell_coord(e.x), cy = cell_coord(e.y);
    const uint32_t cell = uint32_t(cy) * uint32_t(grid) + uint32_t(cx);
    int best = 0;
    float best_dot = -2.0f;
    for (uint32_t k = cell_start[cell]; k < cell_start[cell + 1]; ++k) {
      const int i = cell_candidates[k];
      const float d = glm::dot(unit, directions[i]);
      if (d > best_dot || (d == best_dot && i < best)) {
        best_dot = d;
        best = i;
      }
    }
    return best;
  }
  BOUNCE_HD int cell_coord(float e) const {
    const int c = int((e + 1.0f) * 0.5f * float(grid));
    return c < 0 ? 0 : (c >= grid ? grid - 1 : c);
  }
};

class DirectionSet {
 public:
  // `level` subdivisions of a Platonic solid; directions are the centroids of the spherical
  // faces (vertices projected to the unit sphere at every level, seed Table 3.1).
  static DirectionSet icosahedron(int level);
  static DirectionSet octahedron(int level);
  static DirectionSet tetrahedron(int level);
  // `count` Halton points (bases 2 and 3): z = 1 - 2 u, phi = 2 pi v.
  static DirectionSet halton(int count);
  // 4 level^2 directions: the centres of 2 level equal-angle latitude bands times 2 level
  // equal-angle longitude sectors (the seed's "4L^2" UV grid).
  static DirectionSet uv_grid(int level);
  // The set of `kind` whose size is nearest to `count` (subdivision levels step by 4x; the
  // Halton set takes the count as it is). Throws Error on a count out of [1, 65535].
  static DirectionSet make(DirectionKind kind, int count);
  // Any unit vectors (normalised here); throws Error when empty, too many or degenerate.
  static DirectionSet from_directions(std::vector<vec3> directions, std::string name);

  const std::vector<vec3>& directions() const { return directions_; }
  int size() const { return int(directions_.size()); }
  const std::string& name() const { return name_; }  // e.g. "icosahedron-320"
  int nearest(vec3 unit) const { return view().nearest(unit); }
  // Brute force over every direction: the lookup's specification, for tests.
  int nearest_brute_force(vec3 unit) const;
  DirectionSetView view() const;
  // The longest candidate list of the lookup grid: the lookup's worst-case work.
  int max_candidates() const;

 private:
  void build_lookup();

  std::vector<vec3> directions_;
  std::string name_;
  int grid_ = 0;
  std::vector<uint32_t> cell_start_;
  std::vector<uint16_t> cell_candidates_;
};

const char* direction_kind_name(DirectionKind kind);

// Seed 001 section 3.2's evaluation of a set, over `samples` query directions spread evenly
// over the sphere (a Hammersley set): the angle from a query to its nearest direction, and the
// solid angle each direction answers for (its cell, estimated by the share of queries).
struct DirectionSetQuality {
  double worst_error_deg = 0.0;  // largest angle to the nearest direction (the cover radius)
  double mean_error_deg = 0.0;
  double cell_area_cv = 0.0;     // standard deviation / mean of the cells' solid angles
  double cell_area_ratio = 0.0;  // largest / smallest cell
};
DirectionSetQuality evaluate_direction_set(const DirectionSet& set, int samples);

}  // namespace bounce
