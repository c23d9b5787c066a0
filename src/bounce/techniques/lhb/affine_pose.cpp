#include "bounce/techniques/lhb/affine_pose.h"

#include <algorithm>
#include <cmath>

namespace bounce {
namespace {

// The three edge vectors from anchor 0 (columns); for a flat pose the third is the plane's
// normal with the length of a side, so that a rotation, a uniform scale or a translation carries
// it exactly.
std::optional<mat3> edges(const AffineAnchors& a, std::span<const vec3> p) {
  const vec3 p0 = p[a.index[0]];
  const vec3 e1 = p[a.index[1]] - p0, e2 = p[a.index[2]] - p0;
  vec3 e3 = p[a.index[3]] - p0;
  if (a.flat) {
    const vec3 n = glm::cross(e1, e2);
    const float area = glm::length(n);
    if (!(area > 0.0f)) return std::nullopt;
    e3 = n / std::sqrt(area);
  }
  return mat3(e1, e2, e3);
}

}  // namespace

std::optional<AffineAnchors> AffineAnchors::choose(std::span<const vec3> rest) {
  if (rest.empty()) return std::nullopt;
  AffineAnchors a;
  vec3 lo = rest[0], hi = rest[0];
  for (const vec3& p : rest) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  a.extent = glm::length(hi - lo);
  if (!(a.extent > 0.0f) || !std::isfinite(a.extent)) return std::nullopt;
  const vec3 p0 = rest[0];
  const auto farthest = [&](auto&& measure) {
    uint32_t best = 0;
    float best_value = -1.0f;
    for (uint32_t i = 0; i < rest.size(); ++i) {
      const float v = measure(rest[i] - p0);
      if (v > best_value) {
        best_value = v;
        best = i;
      }
    }
    return std::pair{best, best_value};
  };
  const auto [i1, d1] = farthest([](vec3 e) { return glm::dot(e, e); });
  const vec3 e1 = rest[i1] - p0;
  const auto [i2, area] = farthest([&](vec3 e) { return glm::length(glm::cross(e1, e)); });
  // A line or a point: no plane through the vertices is determined.
  if (!(area > 1e-6f * d1)) return std::nullopt;
  const vec3 n = glm::normalize(glm::cross(e1, rest[i2] - p0));
  const auto [i3, height] = farthest([&](vec3 e) { return std::abs(glm::dot(n, e)); });
  a.index[0] = 0;
  a.index[1] = i1;
  a.index[2] = i2;
  a.index[3] = i3;
  a.flat = !(height > 1e-4f * a.extent);
  const std::optional<mat3> e = edges(a, rest);
  if (!e || !(std::abs(glm::determinant(*e)) > 0.0f)) return std::nullopt;
  a.edges_inverse = glm::inverse(*e);
  return a;
}

std::optional<Affine> fit_affine(const AffineAnchors& anchors, std::span<const vec3> rest,
                                 std::span<const vec3> now, float tolerance) {
  if (rest.size() != now.size() || rest.empty()) return std::nullopt;
  const std::optional<mat3> e = edges(anchors, now);
  if (!e) return std::nullopt;
  Affine map;
  map.linear = *e * anchors.edges_inverse;
  map.offset = now[anchors.index[0]] - map.linear * rest[anchors.index[0]];
  // How much the map stretches lengths at most (bounded by its columns' norms).
  const float stretch = std::max(
      {glm::length(map.linear[0]), glm::length(map.linear[1]), glm::length(map.linear[2]), 1.0f});
  const float limit = tolerance * anchors.extent * stretch;
  for (size_t i = 0; i < rest.size(); ++i) {
    const vec3 miss = map(rest[i]) - now[i];
    // Plus float rounding, which grows with the distance from the origin (a small mesh far out
    // in a level), so that rounding alone never reads as a deformation.
    const vec3 a = glm::abs(now[i]);
    const float slack = limit + 1e-5f * (a.x + a.y + a.z);
    // Also false for NaN.
    if (!(glm::dot(miss, miss) <= slack * slack)) return std::nullopt;
  }
  return map;
}

}  // namespace bounce
