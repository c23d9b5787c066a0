// Precomputed direction sets for the vertex technique's photons (seed 004 §3.4, §5.2.2;
// notes/seed-004.md §2.5-2.6): Saff-Kuijlaars spirals for emission and stratified (or random)
// cosine-weighted bounce directions around a reference normal (+z), rotated into each hit's frame.
// Computed once per parameter change, so every frame's photons follow the same paths where the
// scene did not change (frame coherence).
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/math.h"

namespace bounce {

// n points of a Saff-Kuijlaars spiral (Saff and Kuijlaars 1997) over the zone of the unit sphere
// whose z lies in [z_lo, z_hi]: z evenly spaced (equal areas), the azimuth advanced by
// 3.6 / sqrt(n / f) / sqrt(1 - z^2), f the zone's share of the sphere. The whole sphere (-1, 1)
// is the seed's set; the two extreme points have azimuth 0.
std::vector<vec3> saff_kuijlaars(uint32_t n, float z_lo = -1.0f, float z_hi = 1.0f);

// The same over the hemisphere z >= 0, remapped to be cosine-weighted (z -> sqrt(z), which takes
// equal areas to equal projected areas: Eq 3.10's sqrt).
std::vector<vec3> saff_kuijlaars_cosine(uint32_t n);

// `sets` groups of `count` cosine-weighted directions around +z. Stratified (seed Eq 3.11): an
// M x N grid of strata over (cos^2 theta, phi), M the largest divisor of count not above its
// square root, one jittered direction per stratum; otherwise `count` independent directions.
std::vector<vec3> bounce_direction_sets(uint32_t sets, uint32_t count, bool stratified,
                                        uint32_t seed);

// The strata grid of `count` directions: rows (in theta) and columns (in phi).
struct StrataGrid {
  uint32_t rows, columns;
};
StrataGrid strata_grid(uint32_t count);

}  // namespace bounce
