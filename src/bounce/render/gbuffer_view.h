// GBufferView: the G-buffer's arrays as pointers, for per-pixel kernels (GBuffer::view()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/render/surface_hit.h"

namespace bounce {

inline constexpr uint32_t kNoPrimitive = 0xFFFFFFFFu;

// Field by field as GBuffer (gbuffer.h), which documents them.
template <bool kConst>
struct GBufferViewT {
  template <typename T>
  using Ptr = maybe_const_t<T, kConst>*;

  Ptr<vec3> position = nullptr;
  Ptr<vec3> normal = nullptr;
  Ptr<vec3> geometric_normal = nullptr;
  Ptr<vec3> albedo = nullptr;
  Ptr<float> roughness = nullptr;
  Ptr<vec3> f0 = nullptr;
  Ptr<vec3> emission = nullptr;
  Ptr<float> depth = nullptr;
  Ptr<uint32_t> primitive = nullptr;
  Ptr<uint32_t> mesh = nullptr;
  Ptr<vec2> barycentric = nullptr;
  Ptr<vec2> motion = nullptr;
  int width = 0;
  int height = 0;

  // A writable view reads as a read-only one.
  template <bool kTo>
  requires(kTo && !kConst) BOUNCE_HD operator GBufferViewT<kTo>() const {
    return {position,  normal, geometric_normal, albedo, roughness, f0,    emission, depth,
            primitive, mesh,   barycentric,      motion, width,     height};
  }

  BOUNCE_HD size_t size() const { return size_t(width) * size_t(height); }
  BOUNCE_HD size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  BOUNCE_HD bool hit(size_t i) const { return primitive[i] != kNoPrimitive; }

  // The surface record at pixel i (meaningful where hit(i)).
  BOUNCE_HD SurfaceHit surface(size_t i) const {
    SurfaceHit s;
    s.position = position[i];
    s.normal = normal[i];
    s.geometric_normal = geometric_normal[i];
    s.albedo = albedo[i];
    s.f0 = f0[i];
    s.emission = emission[i];
    s.roughness = roughness[i];
    return s;
  }
  // Writes a surface record's fields at pixel i (the ids, depth and motion are set apart).
  BOUNCE_HD void store(size_t i, const SurfaceHit& s) const {
    // (store3: the G-buffer's runs of pixels write eight lanes at a time.)
    store3(position, i, s.position);
    store3(normal, i, s.normal);
    store3(geometric_normal, i, s.geometric_normal);
    store3(albedo, i, s.albedo);
    store3(f0, i, s.f0);
    store3(emission, i, s.emission);
    roughness[i] = s.roughness;
  }
};
using GBufferView = GBufferViewT<false>;
using ConstGBufferView = GBufferViewT<true>;
static_assert(std::is_trivially_copyable_v<GBufferView>);

}  // namespace bounce
