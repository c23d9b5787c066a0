// Octahedral encoding of unit vectors (Meyer et al. 2010; Cigolle et al. 2014), as seed 000
// stores photon directions: two 16-bit signed-normalised values packed in 32 bits.
#pragma once

#include <cmath>
#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

BOUNCE_HD inline vec2 sign_not_zero(vec2 v) {
  return {v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f};
}

// Unit vector -> point of [-1, 1]^2.
BOUNCE_HD inline vec2 oct_encode(vec3 v) {
  const vec2 p = vec2(v.x, v.y) * (1.0f / (std::abs(v.x) + std::abs(v.y) + std::abs(v.z)));
  return v.z <= 0.0f ? (vec2(1.0f) - glm::abs(vec2(p.y, p.x))) * sign_not_zero(p) : p;
}

BOUNCE_HD inline vec3 oct_decode(vec2 e) {
  vec3 v(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
  if (v.z < 0.0f) {
    const vec2 xy = (vec2(1.0f) - glm::abs(vec2(v.y, v.x))) * sign_not_zero(vec2(v.x, v.y));
    v.x = xy.x;
    v.y = xy.y;
  }
  return glm::normalize(v);
}

BOUNCE_HD inline uint32_t oct_pack(vec3 v) {
  const vec2 e = glm::clamp(oct_encode(v), vec2(-1.0f), vec2(1.0f));
  // Round half away from zero by hand: std::lround is a library call here.
  const auto q = [](float f) {
    const float scaled = f * 32767.0f;
    return uint32_t(int32_t(scaled + (scaled >= 0.0f ? 0.5f : -0.5f)) & 0xFFFF);
  };
  return q(e.x) | (q(e.y) << 16);
}

BOUNCE_HD inline vec3 oct_unpack(uint32_t packed) {
  const auto d = [](uint32_t bits) { return float(int16_t(uint16_t(bits))) / 32767.0f; };
  return oct_decode(vec2(d(packed & 0xFFFF), d(packed >> 16)));
}

}  // namespace bounce
