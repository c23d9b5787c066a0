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

#if defined(__AVX2__) && defined(__FMA__)
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
  const float* normal[3] = {p.prev_surface.nx, p.prev_surface.ny, p.prev_surface.nz};
  for (int c = 0; c < 3; ++c) {
    const __m256 n = _mm256_loadu_ps(taps.normal[c] + x);
    detail::load_taps(normal[c], q, width, t);
    for (int k = 0; k < 4; ++k)
      dot[k] = c == 0 ? _mm256_mul_ps(t[k], n) : _mm256_fmadd_ps(t[k], n, dot[k]);
  }
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
  // The history's eight planes, the history length, then the modulation's six planes:
  // ReprojectedRow's order (past its plane 9, kept; its last, clipped, is the clip's).
  constexpr int kTapped = 15;
  const float* planes[kTapped];
  for (int c = 0; c < 8; ++c) planes[c] = p.prev.c[c];
  planes[8] = p.prev_length;
  const RgbPlanesT<true> modulation[2] = {p.prev_rest.factor, p.prev_rest.emission};
  for (int m = 0; m < 2; ++m) {
    planes[9 + 3 * m] = modulation[m].r;
    planes[10 + 3 * m] = modulation[m].g;
    planes[11 + 3 * m] = modulation[m].b;
  }
  const bool keeps_indirect = p.s.keeps_indirect();
  for (int c = 0; c < kTapped; ++c) {
    float* out = row.v[c < 9 ? c : c + 1] + x;
    if (!keeps_indirect && c >= 4 && c < 8) {  // (none kept: not read, zero as reproject_moved)
      _mm256_storeu_ps(out, _mm256_setzero_ps());
      continue;
    }
    detail::load_taps(planes[c], q, width, t);
    __m256 s = _mm256_mul_ps(w[0], t[0]);
    for (int k = 1; k < 4; ++k) s = _mm256_fmadd_ps(w[k], t[k], s);
    _mm256_storeu_ps(out, _mm256_mul_ps(s, inv));
  }
}

#endif

}  // namespace bounce::denoise
