#include "bounce/techniques/lhb/direction_sets.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "bounce/core/error.h"
#include "bounce/core/qmc.h"
#include "bounce/core/sampling.h"

namespace bounce {

namespace {

using Triangle = std::array<vec3, 3>;

// The faces of a regular solid from its vertices alone: every triple whose three sides all have
// the shortest edge length (true for the tetrahedron, octahedron and icosahedron).
std::vector<Triangle> faces_of(const std::vector<vec3>& vertices) {
  float edge = 1e30f;
  for (size_t i = 0; i < vertices.size(); ++i)
    for (size_t j = i + 1; j < vertices.size(); ++j)
      edge = std::min(edge, glm::distance(vertices[i], vertices[j]));
  const auto adjacent = [&](size_t i, size_t j) {
    return std::abs(glm::distance(vertices[i], vertices[j]) - edge) < 1e-3f * edge;
  };
  std::vector<Triangle> faces;
  for (size_t i = 0; i < vertices.size(); ++i)
    for (size_t j = i + 1; j < vertices.size(); ++j)
      for (size_t k = j + 1; k < vertices.size(); ++k)
        if (adjacent(i, j) && adjacent(j, k) && adjacent(i, k))
          faces.push_back({vertices[i], vertices[j], vertices[k]});
  return faces;
}

// Seed 001 Table 3.1: each face becomes four, the edge midpoints projected onto the sphere.
std::vector<Triangle> subdivide(std::vector<Triangle> faces, int level) {
  for (int l = 0; l < level; ++l) {
    std::vector<Triangle> finer;
    finer.reserve(faces.size() * 4);
    for (const Triangle& t : faces) {
      const vec3 a = glm::normalize(t[0] + t[1]);
      const vec3 b = glm::normalize(t[1] + t[2]);
      const vec3 c = glm::normalize(t[2] + t[0]);
      finer.push_back({t[0], a, c});
      finer.push_back({a, t[1], b});
      finer.push_back({c, b, t[2]});
      finer.push_back({a, b, c});
    }
    faces = std::move(finer);
  }
  return faces;
}

std::vector<vec3> centroids(const std::vector<Triangle>& faces) {
  std::vector<vec3> out;
  out.reserve(faces.size());
  for (const Triangle& t : faces) out.push_back(glm::normalize(t[0] + t[1] + t[2]));
  return out;
}

std::vector<vec3> normalized(std::vector<vec3> v) {
  for (vec3& p : v) p = glm::normalize(p);
  return v;
}

void check_level(int level, const char* solid) {
  if (level < 0 || level > 5) fail("{} subdivision level {} is out of range [0, 5]", solid, level);
}

// Direction of a point of the octahedral square, as the lookup grid maps it.
vec3 oct_point(vec2 e) {
  return oct_decode(e);
}

float angle(vec3 a, vec3 b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
}

}  // namespace

const char* direction_kind_name(DirectionKind kind) {
  switch (kind) {
    case DirectionKind::kIcosahedron:
      return "icosahedron";
    case DirectionKind::kOctahedron:
      return "octahedron";
    case DirectionKind::kTetrahedron:
      return "tetrahedron";
    case DirectionKind::kHalton:
      return "halton";
    case DirectionKind::kUvGrid:
      return "uv-grid";
  }
  return "unknown";
}

DirectionSet DirectionSet::icosahedron(int level) {
  check_level(level, "icosahedron");
  const float g = (1.0f + std::sqrt(5.0f)) * 0.5f;
  std::vector<vec3> v;
  for (float a : {-1.0f, 1.0f})
    for (float b : {-g, g}) {
      v.push_back({0.0f, a, b});
      v.push_back({a, b, 0.0f});
      v.push_back({b, 0.0f, a});
    }
  const auto faces = subdivide(faces_of(normalized(v)), level);
  return from_directions(centroids(faces), fmt::format("icosahedron-{}", faces.size()));
}

DirectionSet DirectionSet::octahedron(int level) {
  check_level(level, "octahedron");
  const std::vector<vec3> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const auto faces = subdivide(faces_of(v), level);
  return from_directions(centroids(faces), fmt::format("octahedron-{}", faces.size()));
}

DirectionSet DirectionSet::tetrahedron(int level) {
  check_level(level, "tetrahedron");
  const std::vector<vec3> v = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const auto faces = subdivide(faces_of(normalized(v)), level);
  return from_directions(centroids(faces), fmt::format("tetrahedron-{}", faces.size()));
}

DirectionSet DirectionSet::halton(int count) {
  if (count < 1 || count > 65535)
    fail("Halton direction count {} is out of range [1, 65535]", count);
  std::vector<vec3> d;
  d.reserve(size_t(count));
  for (int i = 0; i < count; ++i) {
    // Index from 1: point 0 of a radical inverse is 0 in every base (a pole).
    const float z = 1.0f - 2.0f * bounce::halton(0, uint32_t(i + 1));
    const float phi = 2.0f * std::numbers::pi_v<float> * bounce::halton(1, uint32_t(i + 1));
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    d.push_back({s * std::cos(phi), s * std::sin(phi), z});
  }
  return from_directions(std::move(d), fmt::format("halton-{}", count));
}

DirectionSet DirectionSet::uv_grid(int level) {
  if (level < 1 || level > 127) fail("UV grid level {} is out of range [1, 127]", level);
  const int bands = 2 * level, sectors = 2 * level;
  std::vector<vec3> d;
  for (int i = 0; i < bands; ++i) {
    const float theta = (float(i) + 0.5f) * std::numbers::pi_v<float> / float(bands);
    for (int j = 0; j < sectors; ++j) {
      const float phi = (float(j) + 0.5f) * 2.0f * std::numbers::pi_v<float> / float(sectors);
      d.push_back(
          {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  return from_directions(std::move(d), fmt::format("uv-grid-{}", d.size()));
}

DirectionSet DirectionSet::make(DirectionKind kind, int count) {
  if (count < 1 || count > 65535) fail("direction count {} is out of range [1, 65535]", count);
  // The level whose count base * 4^level is nearest to `count` (in ratio).
  const auto level_for = [count](int base) {
    int best = 0;
    double best_gap = 1e30;
    for (int level = 0; level <= 5; ++level) {
      const double gap = std::abs(std::log(double(base) * std::pow(4.0, level) / count));
      if (gap < best_gap) best_gap = gap, best = level;
    }
    return best;
  };
  switch (kind) {
    case DirectionKind::kIcosahedron:
      return icosahedron(level_for(20));
    case DirectionKind::kOctahedron:
      return octahedron(level_for(8));
    case DirectionKind::kTetrahedron:
      return tetrahedron(level_for(4));
    case DirectionKind::kHalton:
      return halton(count);
    case DirectionKind::kUvGrid:
      return uv_grid(std::max(1, int(std::lround(std::sqrt(count / 4.0)))));
  }
  fail("unknown direction set kind {}", int(kind));
}

DirectionSet DirectionSet::from_directions(std::vector<vec3> directions, std::string name) {
  if (directions.empty()) fail("direction set '{}' is empty", name);
  if (directions.size() > 65535)
    fail("direction set '{}' has {} directions (at most 65535)", name, directions.size());
  for (size_t i = 0; i < directions.size(); ++i) {
    const float len = glm::length(directions[i]);
    if (!(len > 1e-6f) || !std::isfinite(len))
      fail("direction set '{}': direction {} has length {}", name, i, len);
    directions[i] /= len;
  }
  DirectionSet set;
  set.directions_ = std::move(directions);
  set.name_ = std::move(name);
  set.build_lookup();
  return set;
}

// Each octahedral cell lies in one quadrant (the grid side is even), where the octahedral map is
// linear on each side of the fold |x| + |y| = 1: the cell is one or two planar pieces of the
// octahedron, and their central projections are spherical polygons whose vertices are the cell's
// corners and the fold's crossings of its sides. For the cell's centre direction c, alpha = the
// largest angle from c to those vertices bounds the cell, and m = the angle from c to its nearest
// direction. A point p of the cell has its nearest direction within alpha + m of p, hence within
// m + 2 alpha of c: the directions within that angle of c are every possible answer.
void DirectionSet::build_lookup() {
  const int n = size();
  grid_ = std::clamp(2 * int(std::ceil(2.0 * std::sqrt(double(n)))), 16, 256);
  const int cells = grid_ * grid_;
  cell_start_.assign(size_t(cells) + 1, 0);
  cell_candidates_.clear();
  std::vector<float> angles(static_cast<size_t>(n));
  const float step = 2.0f / float(grid_);
  for (int cy = 0; cy < grid_; ++cy)
    for (int cx = 0; cx < grid_; ++cx) {
      const vec2 lo(-1.0f + float(cx) * step, -1.0f + float(cy) * step);
      const vec2 hi = lo + vec2(step);
      const vec2 mid = 0.5f * (lo + hi);
      const vec3 c = oct_point(mid);
      const std::array<vec2, 4> corner = {lo, vec2(hi.x, lo.y), hi, vec2(lo.x, hi.y)};
      const vec2 s(mid.x >= 0.0f ? 1.0f : -1.0f, mid.y >= 0.0f ? 1.0f : -1.0f);
      float alpha = 0.0f;
      for (int k = 0; k < 4; ++k) {
        const vec2 a = corner[size_t(k)], b = corner[size_t((k + 1) % 4)];
        alpha = std::max(alpha, angle(c, oct_point(a)));
        const float fa = s.x * a.x + s.y * a.y - 1.0f, fb = s.x * b.x + s.y * b.y - 1.0f;
        if ((fa < 0.0f) != (fb < 0.0f)) {
          const float t = fa / (fa - fb);
          alpha = std::max(alpha, angle(c, oct_point(a + t * (b - a))));
        }
      }
      float m = 1e30f;
      for (int i = 0; i < n; ++i) {
        angles[size_t(i)] = angle(c, directions_[size_t(i)]);
        m = std::min(m, angles[size_t(i)]);
      }
      // The margin covers float rounding in the angles (1e-3 rad, far above acos's error).
      const float reach = m + 2.0f * alpha + 1e-3f;
      for (int i = 0; i < n; ++i)
        if (angles[size_t(i)] <= reach) cell_candidates_.push_back(uint16_t(i));
      cell_start_[size_t(cy * grid_ + cx) + 1] = uint32_t(cell_candidates_.size());
    }
}

int DirectionSet::nearest_brute_force(vec3 unit) const {
  int best = 0;
  float best_dot = -2.0f;
  for (int i = 0; i < size(); ++i) {
    const float d = glm::dot(unit, directions_[size_t(i)]);
    if (d > best_dot) best_dot = d, best = i;
  }
  return best;
}

DirectionSetView DirectionSet::view() const {
  return {directions_.data(), size(), grid_, cell_start_.data(), cell_candidates_.data()};
}

int DirectionSet::max_candidates() const {
  uint32_t most = 0;
  for (size_t c = 0; c + 1 < cell_start_.size(); ++c)
    most = std::max(most, cell_start_[c + 1] - cell_start_[c]);
  return int(most);
}

DirectionSetQuality evaluate_direction_set(const DirectionSet& set, int samples) {
  if (samples < 1) fail("direction set evaluation needs at least one sample, got {}", samples);
  std::vector<uint64_t> hits(size_t(set.size()), 0);
  double worst = 0.0, sum = 0.0;
  for (int k = 0; k < samples; ++k) {
    const vec3 q = sample_uniform_sphere(hammersley(uint32_t(k), uint32_t(samples)));
    const int i = set.nearest(q);
    const double a =
        std::acos(std::clamp(double(glm::dot(q, set.directions()[size_t(i)])), -1.0, 1.0));
    worst = std::max(worst, a);
    sum += a;
    ++hits[size_t(i)];
  }
  double mean_hits = double(samples) / double(set.size()), var = 0.0;
  uint64_t most = 0, least = ~uint64_t(0);
  for (uint64_t h : hits) {
    var += (double(h) - mean_hits) * (double(h) - mean_hits);
    most = std::max(most, h);
    least = std::min(least, h);
  }
  const double degrees = 180.0 / std::numbers::pi;
  DirectionSetQuality q;
  q.worst_error_deg = worst * degrees;
  q.mean_error_deg = sum / double(samples) * degrees;
  q.cell_area_cv = std::sqrt(var / double(set.size())) / mean_hits;
  q.cell_area_ratio =
      least > 0 ? double(most) / double(least) : std::numeric_limits<double>::infinity();
  return q;
}

}  // namespace bounce
