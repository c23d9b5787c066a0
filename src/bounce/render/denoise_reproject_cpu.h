// The temporal pass's reprojection (denoise_temporal.h's reproject_moved) on the CPU, eight pixels
// of a row at a time with AVX2. The CPU has no fast gather: GCC's vectorised reproject_moved loads
// each pixel's 4 taps x 14 planes one float at a time, about 100 cycles a pixel and most of the
// temporal pass (1280x720 in motion: 12 of its 21 ms). Here each row of a pixel's bilinear block
// is one 8-byte load per plane (bilinear_taps places the block inside the image, so its two
// columns are adjacent), eight pixels' pairs are shuffled into two vectors, and the planes are
// walked one after another, so few pointers are live. The arithmetic is reproject_moved's in the
// same order; tests check the two agree.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bounce/render/denoise_temporal.h"

#if defined(__AVX2__) && defined(__FMA__) && defined(__F16C__)
#include <immintrin.h>
#define BOUNCE_REPROJECT_EIGHT 1
#else
#define BOUNCE_REPROJECT_EIGHT 0
#endif

namespace bounce::denoise {

// A row's bilinear footprints (bilinear_taps) and its pixels' normals as planes, which the CPU's
// first loop over the row fills (vectorised by the compiler) for reproject_eight.
struct TapRow {
  int* q = nullptr;
  float* w[4] = {};
  float* normal[3] = {};

  // Over `q` (width entries) and `planes` (7 x width: the weights, then the normals).
  static TapRow over(int* q, float* planes, size_t width) {
    TapRow t;
    t.q = q;
    for (int k = 0; k < 4; ++k) t.w[k] = planes + size_t(k) * width;
    for (int c = 0; c < 3; ++c) t.normal[c] = planes + size_t(4 + c) * width;
    return t;
  }

  BOUNCE_LANE_INLINE void store(const TemporalPass& p, int x, int y, size_t i) const {
    const BilinearTaps t = bilinear_taps(p, x, y, i);
    // (Written out: a loop over the planes keeps the row loop from vectorising.)
    q[x] = t.q;
    w[0][x] = t.w[0];
    w[1][x] = t.w[1];
    w[2][x] = t.w[2];
    w[3][x] = t.w[3];
    const vec3 n = p.g.normal[i];
    normal[0][x] = n.x;
    normal[1][x] = n.y;
    normal[2][x] = n.z;
  }
};

// Whether reproject_eight serves this pass: the last frame's block pairs need two columns and
// two rows (and the CPU AVX2).
inline bool reproject_eight_fits(const TemporalPass& p) {
  return BOUNCE_REPROJECT_EIGHT && p.prev_width >= 2 && p.prev_height >= 2;
}

#if BOUNCE_REPROJECT_EIGHT

namespace detail {

// Plane `a` at the block rows of eight pixels (first pixels q[0..7], plus `row`: 0 or the
// width): the block's first and second columns as two vectors, pixel by pixel.
inline __attribute__((always_inline)) void load_pairs(const float* a, const int* q, int row,
                                                      __m256& c0, __m256& c1) {
  auto two = [&](int l) __attribute__((always_inline)) {
    const __m128 lo =
        _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(a + q[l] + row)));
    return _mm_loadh_pi(lo, reinterpret_cast<const __m64*>(a + q[l + 1] + row));
  };
  // Pixels 0 1 | 4 5 and 2 3 | 6 7, each pixel's two columns side by side.
  const __m256 v0 = _mm256_insertf128_ps(_mm256_castps128_ps256(two(0)), two(4), 1);
  const __m256 v1 = _mm256_insertf128_ps(_mm256_castps128_ps256(two(2)), two(6), 1);
  c0 = _mm256_shuffle_ps(v0, v1, _MM_SHUFFLE(2, 0, 2, 0));
  c1 = _mm256_shuffle_ps(v0, v1, _MM_SHUFFLE(3, 1, 3, 1));
}

// The four taps (reproject_moved's order) of plane `a` for eight pixels; starts fetching the
// plane's rows further along (the next pixels' blocks, where motion is smooth).
inline __attribute__((always_inline)) void load_taps(const float* a, const int* q, int width,
                                                     __m256 (&t)[4]) {
  constexpr int kAhead = 32;  // floats: measured best of 0, 32, 64 and 128 at 1280x720
  _mm_prefetch(reinterpret_cast<const char*>(a + q[0] + kAhead), _MM_HINT_T0);
  _mm_prefetch(reinterpret_cast<const char*>(a + q[0] + width + kAhead), _MM_HINT_T0);
  load_pairs(a, q, 0, t[0], t[1]);
  load_pairs(a, q, width, t[2], t[3]);
}

// The floats of eight words of two halves each (core/half_float.h): the low halves into `lo`,
// the high into `hi`, with F16C's conversion (exact for the normal halves and zeros stored).
inline __attribute__((always_inline)) void halves(__m256 words, __m256& lo, __m256& hi) {
  // Within each 128-bit lane: the four low halves, then the four high ones.
  const __m256i order = _mm256_setr_epi8(0, 1, 4, 5, 8, 9, 12, 13, 2, 3, 6, 7, 10, 11, 14, 15, 0, 1,
                                         4, 5, 8, 9, 12, 13, 2, 3, 6, 7, 10, 11, 14, 15);
  const __m256i s = _mm256_shuffle_epi8(_mm256_castps_si256(words), order);
  const __m256i p = _mm256_permute4x64_epi64(s, _MM_SHUFFLE(3, 1, 2, 0));
  lo = _mm256_cvtph_ps(_mm256_castsi256_si128(p));
  hi = _mm256_cvtph_ps(_mm256_extracti128_si256(p, 1));
}

inline __attribute__((always_inline)) void tap_halves(const __m256 (&words)[4], __m256 (&lo)[4],
                                                      __m256 (&hi)[4]) {
  for (int k = 0; k < 4; ++k) halves(words[k], lo[k], hi[k]);
}

}  // namespace detail

// reproject_moved for the eight pixels x .. x + 7 of row y (inside this frame), from `taps`
// (TapRow::store at those pixels), into `row` at x .. x + 7. Needs reproject_eight_fits(p).
inline void reproject_eight(const TemporalPass& p, const TapRow& taps, int x, int y,
                            const ReprojectedRow& row) {
  const size_t i = size_t(y) * size_t(p.width) + size_t(x);
  const int* q = taps.q + x;
  const int width = p.prev_width;
  const __m256 z = _mm256_loadu_ps(p.g.depth + i);
  const __m256 dz_max = _mm256_mul_ps(_mm256_set1_ps(p.s.depth_tolerance), z);
  const __m256i object = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p.g.mesh + i));
  const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  __m256 t[4], same[4], dot[4];
  detail::load_taps(reinterpret_cast<const float*>(p.prev_surface.object), q, width, t);
  for (int k = 0; k < 4; ++k)
    same[k] = _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_castps_si256(t[k]), object));
  detail::load_taps(p.prev_surface.depth, q, width, t);
  for (int k = 0; k < 4; ++k) {
    const __m256 dz = _mm256_and_ps(_mm256_sub_ps(t[k], z), abs_mask);
    same[k] = _mm256_and_ps(same[k], _mm256_cmp_ps(dz, dz_max, _CMP_LE_OQ));
  }
  // Last frame's normals from its packed planes (nx | ny, nz | length): the length's taps are
  // kept for the sums below.
  const auto packed = [&](int k) { return reinterpret_cast<const float*>(p.prev_packed.w[k]); };
  __m256 words[4], lo[4], hi[4], length[4];
  detail::load_taps(packed(0), q, width, words);
  detail::tap_halves(words, lo, hi);
  for (int k = 0; k < 4; ++k) dot[k] = _mm256_mul_ps(lo[k], _mm256_loadu_ps(taps.normal[0] + x));
  for (int k = 0; k < 4; ++k)
    dot[k] = _mm256_fmadd_ps(hi[k], _mm256_loadu_ps(taps.normal[1] + x), dot[k]);
  detail::load_taps(packed(1), q, width, words);
  detail::tap_halves(words, lo, length);
  for (int k = 0; k < 4; ++k)
    dot[k] = _mm256_fmadd_ps(lo[k], _mm256_loadu_ps(taps.normal[2] + x), dot[k]);
  const __m256 tolerance = _mm256_set1_ps(p.s.normal_tolerance);
  __m256 w[4];
  for (int k = 0; k < 4; ++k) {
    same[k] = _mm256_and_ps(same[k], _mm256_cmp_ps(dot[k], tolerance, _CMP_GE_OQ));
    w[k] = _mm256_and_ps(_mm256_loadu_ps(taps.w[k] + x), same[k]);
  }
  const __m256 weight = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(w[0], w[1]), w[2]), w[3]);
  const __m256i primitive = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p.g.primitive + i));
  const __m256 no_hit =
      _mm256_castsi256_ps(_mm256_cmpeq_epi32(primitive, _mm256_set1_epi32(int32_t(kNoPrimitive))));
  const __m256 kept = _mm256_andnot_ps(
      no_hit, _mm256_cmp_ps(weight, _mm256_set1_ps(kMinHistoryWeight), _CMP_GE_OQ));
  const __m256 inv = _mm256_and_ps(_mm256_div_ps(_mm256_set1_ps(1.0f), weight), kept);
  _mm256_storeu_ps(row.v[9] + x, _mm256_and_ps(kept, _mm256_set1_ps(1.0f)));
  // The taps' weighted sum, normalised, into ReprojectedRow's plane c.
  const auto store = [&](int c, const __m256(&taps4)[4]) __attribute__((always_inline)) {
    __m256 s = _mm256_mul_ps(w[0], taps4[0]);
    for (int k = 1; k < 4; ++k) s = _mm256_fmadd_ps(w[k], taps4[k], s);
    _mm256_storeu_ps(row.v[c] + x, _mm256_mul_ps(s, inv));
  };
  // The history's eight planes (ReprojectedRow's first eight).
  const bool keeps_indirect = p.s.keeps_indirect();
  for (int c = 0; c < 8; ++c) {
    if (!keeps_indirect && c >= 4) {  // (none kept: not read, zero as reproject_moved)
      _mm256_storeu_ps(row.v[c] + x, _mm256_setzero_ps());
      continue;
    }
    detail::load_taps(p.prev.c[c], q, width, t);
    store(c, t);
  }
  // The history length (plane 8; plane 9, kept, is above), then the modulation's factor rgb and
  // emission rgb (planes 10-15; the last, clipped, is the clip's), from the packed planes.
  store(8, length);
  for (int k = 2; k < 5; ++k) {
    detail::load_taps(packed(k), q, width, words);
    detail::tap_halves(words, lo, hi);
    store(2 * k + 6, lo);
    store(2 * k + 7, hi);
  }
}

namespace detail {
// The half bits of eight floats, as half_bits makes them: magnitudes clamped to the largest half
// (NaN and infinities too), those below the smallest normal half flushed to a signed zero, then
// F16C's conversion, rounding to nearest even.
inline __attribute__((always_inline)) __m128i half_bits8(__m256 v) {
  const __m256i u = _mm256_castps_si256(v);
  const __m256i sign = _mm256_and_si256(u, _mm256_set1_epi32(int(0x80000000u)));
  __m256i a = _mm256_and_si256(u, _mm256_set1_epi32(0x7FFFFFFF));
  a = _mm256_min_epu32(a, _mm256_set1_epi32(int(kHalfMaxBits)));
  a = _mm256_and_si256(a, _mm256_cmpgt_epi32(a, _mm256_set1_epi32(int(kHalfMinNormalBits - 1))));
  return _mm256_cvtps_ph(_mm256_castsi256_ps(_mm256_or_si256(sign, a)), _MM_FROUND_TO_NEAREST_INT);
}
// Words of the halves of a (low) and b (high), eight of each, into out[0..7].
inline __attribute__((always_inline)) void store_pairs(__m256 a, __m256 b, uint32_t* out) {
  const __m128i ha = half_bits8(a), hb = half_bits8(b);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_unpacklo_epi16(ha, hb));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4), _mm_unpackhi_epi16(ha, hb));
}
}  // namespace detail
#endif

// Row y's packed planes (PackedPlanes) from what the blend wrote there (temporal_blend with kPack
// false): eight pixels at a time with F16C where the CPU has it, the same words as
// PackedPlanes::set.
inline void pack_row(const TemporalPass& p, int y) {
  const size_t first = size_t(y) * size_t(p.width);
  const PackedPlanes out = p.packed;
  const SurfacePlanes s = p.surface;
  const RgbPlanes f = p.rest.factor, e = p.rest.emission;
  size_t i = first;
  const size_t end = first + size_t(p.width);
#if BOUNCE_REPROJECT_EIGHT
  const auto at = [&](const float* plane) { return _mm256_loadu_ps(plane + i); };
  for (; i + 8 <= end; i += 8) {
    detail::store_pairs(at(s.nx), at(s.ny), out.w[0] + i);
    detail::store_pairs(at(s.nz), at(p.length), out.w[1] + i);
    detail::store_pairs(at(f.r), at(f.g), out.w[2] + i);
    detail::store_pairs(at(f.b), at(e.r), out.w[3] + i);
    detail::store_pairs(at(e.g), at(e.b), out.w[4] + i);
  }
#endif
  for (; i < end; ++i) out.set(i, s.normal(i), p.length[i], f.get(i), e.get(i));
}

}  // namespace bounce::denoise
