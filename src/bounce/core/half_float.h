// Two floats in one 32-bit word as IEEE half-precision values (binary16), for planes that a
// gather reads many of: half the bytes, so half the cache lines, per value. Encoding rounds to
// nearest even, clamps magnitudes past the largest half (65504) to it and flushes those below
// the smallest normal half (2^-14) to zero, so only normal halves and zero are ever stored, and
// decoding is exact. Branch-free integer code, so the CPU's row loops vectorise it; the CPU's
// AVX2 reprojection decodes the same bits the same way (render/denoise_reproject_cpu.h).
#pragma once

#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#if !BOUNCE_DEVICE_CODE
#include <bit>
#endif

namespace bounce {

BOUNCE_HD BOUNCE_LANE_INLINE uint32_t float_bits(float f) {
#if BOUNCE_DEVICE_CODE
  return __float_as_uint(f);
#else
  return std::bit_cast<uint32_t>(f);
#endif
}
BOUNCE_HD BOUNCE_LANE_INLINE float bits_float(uint32_t u) {
#if BOUNCE_DEVICE_CODE
  return __uint_as_float(u);
#else
  return std::bit_cast<float>(u);
#endif
}

inline constexpr uint32_t kHalfMaxBits = 0x477FE000u;        // 65504 as a float's bits
inline constexpr uint32_t kHalfMinNormalBits = 0x38800000u;  // 2^-14
inline constexpr uint32_t kHalfRebias = 112u << 23;          // float bias 127 less half bias 15

// The half nearest f (ties to even) as its 16 bits; see above for the range. Not for NaN.
BOUNCE_HD BOUNCE_LANE_INLINE uint32_t half_bits(float f) {
  const uint32_t u = float_bits(f);
  const uint32_t sign = (u >> 16) & 0x8000u;
  uint32_t a = u & 0x7FFFFFFFu;
  a = a < kHalfMaxBits ? a : kHalfMaxBits;  // (positive floats order as their bits do)
  const uint32_t r = a - kHalfRebias;
  // Round the 13 bits dropped to nearest, ties to the even half; a carry moves the exponent on.
  const uint32_t h = (r + 0x0FFFu + ((r >> 13) & 1u)) >> 13;
  return sign | pick(a >= kHalfMinNormalBits, h, 0u);
}

// The float of half bits h (its low 16 bits): zero or a normal half, as half_bits writes.
BOUNCE_HD BOUNCE_LANE_INLINE float half_float(uint32_t h) {
  const uint32_t a = h & 0x7FFFu;
  const uint32_t magnitude = pick(a != 0u, (a << 13) + kHalfRebias, 0u);
  return bits_float(((h & 0x8000u) << 16) | magnitude);
}

// a in the low half of a word, b in the high.
BOUNCE_HD BOUNCE_LANE_INLINE uint32_t pack_halves(float a, float b) {
  return half_bits(a) | (half_bits(b) << 16);
}
BOUNCE_HD BOUNCE_LANE_INLINE float low_half(uint32_t w) {
  return half_float(w);
}
BOUNCE_HD BOUNCE_LANE_INLINE float high_half(uint32_t w) {
  return half_float(w >> 16);
}

}  // namespace bounce
