// Helpers for bodies that a CPU row loop vectorises (docs/architecture.md): GCC's vectoriser
// gives up on a branch, a whole-struct copy or a select between structs, so selects are bit
// operations and vec3 values move component by component.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#if !BOUNCE_DEVICE_CODE
#include <bit>
#endif

namespace bounce {

// c ? a : b as bit operations: no branch for the compiler to thread on, so a row loop full of
// them stays one basic block and vectorises. (The unchosen value may be NaN: it is masked away.)
BOUNCE_HD BOUNCE_LANE_INLINE uint32_t pick(bool c, uint32_t a, uint32_t b) {
  const uint32_t m = 0u - uint32_t(c);
  return (a & m) | (b & ~m);
}
BOUNCE_HD BOUNCE_LANE_INLINE float pick(bool c, float a, float b) {
#if BOUNCE_DEVICE_CODE
  return c ? a : b;
#else
  return std::bit_cast<float>(pick(c, std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b)));
#endif
}
BOUNCE_HD BOUNCE_LANE_INLINE vec3 pick(bool c, vec3 a, vec3 b) {
  return {pick(c, a.x, b.x), pick(c, a.y, b.y), pick(c, a.z, b.z)};
}
BOUNCE_HD BOUNCE_LANE_INLINE vec4 pick(bool c, vec4 a, vec4 b) {
  return {pick(c, a.x, b.x), pick(c, a.y, b.y), pick(c, a.z, b.z), pick(c, a.w, b.w)};
}

// Element i of a vec3 array, read component by component.
BOUNCE_HD BOUNCE_LANE_INLINE vec3 load3(const vec3* a, size_t i) {
  return {a[i].x, a[i].y, a[i].z};
}
// A vec3 field, read component by component.
BOUNCE_HD BOUNCE_LANE_INLINE vec3 load3(const vec3& v) {
  return {v.x, v.y, v.z};
}
BOUNCE_HD BOUNCE_LANE_INLINE void store3(vec3* a, size_t i, vec3 v) {
  a[i].x = v.x;
  a[i].y = v.y;
  a[i].z = v.z;
}

}  // namespace bounce
