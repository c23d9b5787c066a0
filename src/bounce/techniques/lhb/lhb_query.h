// The ray query through the layered hit buffers (seed 001, sections 5.3 and 5.5): the closest
// surface from a point along one of the buffers' directions. The origin is projected into the
// buffer; the texel's sorted list (static and moving slabs) gives the first element deeper than
// the origin by more than tmin. With a jitter the projected position moves within the texel grid
// first: the seed's cone approximation, where a disc of radius r texels stands for the cone of
// directions that snap to this one.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/techniques/lhb/lhb_view.h"

namespace bounce {

struct LhbHit {
  static constexpr uint32_t kNone = 0xFFFFFFFFu;
  uint32_t prim = kNone;                             // global triangle id
  float t = std::numeric_limits<float>::infinity();  // distance along the buffer's direction

  BOUNCE_HD bool valid() const { return prim != kNone; }
};

// The first element of a sorted list deeper than min_depth, skipping `skip` (the triangle the
// ray leaves, when the caller knows it); the list is sorted, so the walk stops at the first.
BOUNCE_HD inline LhbHit lhb_first_beyond(const LhbElement* list, int count, float min_depth,
                                         uint32_t skip) {
  for (int i = 0; i < count; ++i)
    if (list[i].depth > min_depth && list[i].prim != skip) return {list[i].prim, list[i].depth};
  return {};
}

// Closest hit from `origin` along buffer `direction`: elements with depth > depth(origin) + tmin.
// `jitter` shifts the projected position by that many texels (0 for the exact ray).
// The returned t is the distance along the direction; the hit point is lhb_hit_point's.
BOUNCE_HD inline LhbHit lhb_closest(const LhbView& view, int direction, vec3 origin, float tmin,
                                    vec2 jitter = vec2(0.0f), uint32_t skip = LhbHit::kNone) {
  const LhbFrame& f = view.frames[direction];
  const vec2 xy = f.texel_coords(origin) + jitter;
  const float fx = std::floor(xy.x), fy = std::floor(xy.y);
  if (!(fx >= 0.0f && fy >= 0.0f && fx < float(view.size) && fy < float(view.size))) return {};
  const size_t texel = view.texel(direction, int(fx), int(fy));
  const float z = f.depth(origin);
  LhbHit best =
      lhb_first_beyond(view.static_slab.list(texel), view.static_slab.kept(texel), z + tmin, skip);
  if (!view.dynamic_slab.empty()) {
    const LhbHit moving = lhb_first_beyond(view.dynamic_slab.list(texel),
                                           view.dynamic_slab.kept(texel), z + tmin, skip);
    if (moving.t < best.t) best = moving;
  }
  if (best.valid()) best.t -= z;
  return best;
}

// Where a hit of lhb_closest lies: on the (jittered) texel ray, t along the direction.
BOUNCE_HD inline vec3 lhb_hit_point(const LhbView& view, int direction, vec3 origin, vec2 jitter,
                                    const LhbHit& hit) {
  const LhbFrame& f = view.frames[direction];
  return origin + f.across(jitter) + hit.t * f.d;
}

}  // namespace bounce
