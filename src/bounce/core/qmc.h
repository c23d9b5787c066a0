// Quasi-Monte Carlo sequences: radical inverse, Hammersley (seed 000 Listing 5.6, typos fixed),
// Halton and the first two dimensions of Sobol'.
#pragma once

#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

BOUNCE_HD inline uint32_t reverse_bits(uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return bits;
}

// Converts 32 fixed-point bits to a float in [0, 1), rounding down so 1 is never returned.
BOUNCE_HD inline float bits_to_unit_float(uint32_t bits) {
  return float(bits >> 8) * (1.0f / 16777216.0f);
}

// Van der Corput sequence: the base-2 radical inverse of i.
BOUNCE_HD inline float radical_inverse2(uint32_t i) {
  return bits_to_unit_float(reverse_bits(i));
}

// Radical inverse of i in any base >= 2 (double precision for long sequences).
BOUNCE_HD inline float radical_inverse(uint32_t base, uint32_t i) {
  const double inv_base = 1.0 / base;
  double inv = inv_base, result = 0.0;
  while (i > 0) {
    result += double(i % base) * inv;
    i /= base;
    inv *= inv_base;
  }
  return float(result < 1.0 ? result : 0x1.fffffep-1);
}

// The screen lattice: for pixel (x, y), two 32-bit fixed-point coordinates in [0, 1) whose
// values at neighbouring pixels spread evenly, so that samples drawn with them (after one random
// rotation for the whole screen) are stratified across each small block of pixels, and a spatial
// filter's average over the block errs less than over independent samples. A rank-1 lattice of
// the plane: each coordinate is x * a + y * b (mod 1); the first takes the R2 sequence's
// constants (Roberts 2018, "The unreasonable effectiveness of quasirandom sequences"), which
// alone serve as a 1D mask, the second the golden ratio's and sqrt(2)'s fractional parts. In
// windows of 4x4 to 8x8 pixels the closest two points are 0.40-0.62 of the even spacing apart
// (independent uniform points: about 0.1). Fixed point, so exact at any resolution.
BOUNCE_HD inline uint32_t screen_lattice_x(uint32_t x, uint32_t y) {
  return x * 3242174889u + y * 2447445414u;
}
BOUNCE_HD inline uint32_t screen_lattice_y(uint32_t x, uint32_t y) {
  return x * 2654435769u + y * 1779033704u;
}

// Point i of an N-point 2D Hammersley set: (i / N, radical_inverse2(i)).
BOUNCE_HD inline vec2 hammersley(uint32_t i, uint32_t n) {
  return {float(i) / float(n), radical_inverse2(i)};
}

// Halton point in dimension `dim` (0-based), using the dim-th prime as the base; up to 16 dims.
float halton(uint32_t dim, uint32_t i);

// The first two dimensions of the Sobol' sequence: a (0,2)-sequence in base 2, so every
// power-of-two prefix is stratified into every elementary interval.
BOUNCE_HD inline vec2 sobol2(uint32_t i) {
  uint32_t y = 0;
  // Dimension 1's generator matrix columns are v_k = v_{k-1} ^ (v_{k-1} >> 1), v_0 = 1 << 31.
  for (uint32_t k = i, v = 1u << 31; k; k >>= 1, v ^= v >> 1)
    if (k & 1u) y ^= v;
  return {radical_inverse2(i), bits_to_unit_float(y)};
}

// Cranley-Patterson rotation: shifts a point set by `offset` modulo 1 (per-pixel decorrelation).
BOUNCE_HD inline vec2 rotate_unit(vec2 u, vec2 offset) {
  return glm::fract(u + offset);
}

}  // namespace bounce
