#include "bounce/techniques/vertex/point_sets.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"

namespace bounce {

std::vector<vec3> saff_kuijlaars(uint32_t n, float z_lo, float z_hi) {
  std::vector<vec3> points(n);
  if (n == 0) return points;
  if (n == 1) {
    const float z = 0.5f * (z_lo + z_hi);
    points[0] = vec3(std::sqrt(std::max(0.0f, 1.0f - z * z)), 0.0f, z);
    return points;
  }
  const double share = std::max(1e-6, double(z_hi - z_lo) / 2.0);
  const double step = 3.6 * std::sqrt(share / double(n));
  double phi = 0.0;
  for (uint32_t k = 0; k < n; ++k) {
    const double z = double(z_lo) + double(z_hi - z_lo) * double(k) / double(n - 1);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - z * z));
    if (k == 0 || k == n - 1)
      phi = 0.0;
    else
      phi = std::fmod(phi + step / std::max(sin_theta, 1e-6), 2.0 * kPi);
    points[k] = vec3(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(z));
  }
  return points;
}

std::vector<vec3> saff_kuijlaars_cosine(uint32_t n) {
  // Keep the spiral off the rim (z = 0 would graze the surface): the zone [0.5/n, 1].
  std::vector<vec3> points = saff_kuijlaars(n, 0.5f / float(std::max(n, 1u)), 1.0f);
  for (vec3& p : points) {
    const float z = std::sqrt(p.z);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float s = std::sqrt(p.x * p.x + p.y * p.y);
    p = s > 0.0f ? vec3(p.x / s * r, p.y / s * r, z) : vec3(r, 0.0f, z);
  }
  return points;
}

StrataGrid strata_grid(uint32_t count) {
  uint32_t rows = 1;
  for (uint32_t m = 1; m * m <= count; ++m)
    if (count % m == 0) rows = m;
  return {rows, count / std::max(rows, 1u)};
}

std::vector<vec3> bounce_direction_sets(uint32_t sets, uint32_t count, bool stratified,
                                        uint32_t seed) {
  std::vector<vec3> dirs(size_t(sets) * count);
  const StrataGrid grid = strata_grid(count);
  for (uint32_t s = 0; s < sets; ++s) {
    TeaRng rng = TeaRng::for_path(s, seed ^ 0x51ed270bu);
    for (uint32_t k = 0; k < count; ++k) {
      vec2 u = rng.next2();
      if (stratified) {
        // Eq 3.11: theta = acos(sqrt((j - xi1) / M)), phi = 2 pi (i - xi2) / N.
        const uint32_t j = k / grid.columns, i = k % grid.columns;
        u = vec2((float(j) + u.x) / float(grid.rows), (float(i) + u.y) / float(grid.columns));
      }
      // sample_cosine_hemisphere takes cos^2 theta from one coordinate and phi from the other;
      // written out here so the strata are exactly Eq 3.11's.
      const float cos_theta = std::sqrt(std::max(1e-6f, 1.0f - u.x));
      const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
      const float phi = kTwoPi * u.y;
      dirs[size_t(s) * count + k] =
          vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
    }
  }
  return dirs;
}

}  // namespace bounce
