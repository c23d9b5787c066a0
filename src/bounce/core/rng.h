// Pseudo-random numbers: TEA (seed 000 §5.3.1, after Zafar et al. 2010) for per-path seeds on
// GPU-style kernels, and PCG32 (O'Neill 2014) as the general-purpose generator.
#pragma once

#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Tiny Encryption Algorithm with N rounds: a hash of two words into two words.
template <unsigned N>
BOUNCE_HD inline uvec2 tea(uint32_t v0, uint32_t v1) {
  uint32_t sum = 0;
  for (unsigned i = 0; i < N; ++i) {
    sum += 0x9E3779B9u;
    v0 += ((v1 << 4) + 0xA341316Cu) ^ (v1 + sum) ^ ((v1 >> 5) + 0xC8013EA4u);
    v1 += ((v0 << 4) + 0xAD90777Du) ^ (v0 + sum) ^ ((v0 >> 5) + 0x7E95761Eu);
  }
  return {v0, v1};
}

// The seed's per-path generator: seeded with TEA<16>, advanced with TEA<8>, 24-bit floats.
struct TeaRng {
  uvec2 state;

  BOUNCE_HD static TeaRng for_path(uint32_t index, uint32_t stream = 0) {
    return {tea<16>(index, index * 1664525u + stream)};
  }
  BOUNCE_HD vec2 next2() {
    state = tea<8>(state.x, state.y);
    return vec2(float(state.x & 0x00FFFFFFu), float(state.y & 0x00FFFFFFu)) * (1.0f / 16777216.0f);
  }
};

// PCG32 (XSH RR variant): small state, good statistics, cheap to seed per pixel.
struct Pcg32 {
  uint64_t state = 0x853c49e6748fea9bULL;
  uint64_t inc = 0xda3e39cb94b95bdbULL;

  Pcg32() = default;
  BOUNCE_HD Pcg32(uint64_t seed, uint64_t stream = 1) {
    state = 0;
    inc = (stream << 1u) | 1u;
    next_u32();
    state += seed;
    next_u32();
  }
  BOUNCE_HD uint32_t next_u32() {
    const uint64_t old = state;
    state = old * 6364136223846793005ULL + inc;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }
  // Uniform in [0, 1): the top 24 bits, so the result is exactly representable and never 1.
  BOUNCE_HD float next_float() { return float(next_u32() >> 8) * (1.0f / 16777216.0f); }
  BOUNCE_HD vec2 next2() { return {next_float(), next_float()}; }
  // Uniform integer in [0, bound) without modulo bias (Lemire's method).
  BOUNCE_HD uint32_t next_below(uint32_t bound) {
    uint64_t m = uint64_t(next_u32()) * bound;
    uint32_t low = uint32_t(m);
    if (low < bound) {
      const uint32_t threshold = (~bound + 1u) % bound;
      while (low < threshold) {
        m = uint64_t(next_u32()) * bound;
        low = uint32_t(m);
      }
    }
    return uint32_t(m >> 32);
  }
};

// A 32-bit integer hash (Wellons' "lowbias32"), for decorrelating per-pixel sequences.
BOUNCE_HD inline uint32_t hash_u32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

}  // namespace bounce
