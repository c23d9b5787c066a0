// The ray query through the layered hit buffers (seed 001, sections 5.3 and 5.5): the closest
// surface from a point along one of the buffers' directions. The origin is projected into the
// buffer; the texel's sorted list (static and moving slabs) gives the first element deeper than
// the origin by more than tmin. With a jitter the projected position moves within the texel grid
// first: the seed's cone approximation, where a disc of radius r texels stands for the cone of
// directions that snap to this one. Instances (moving meshes re-posed by a transform) are
// entered through their own frames.
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
  vec3 point{0.0f};  // the hit in the world: on the (jittered) origin's line along the direction

  BOUNCE_HD bool valid() const { return prim != kNone; }
};

// The first element of a sorted list deeper than min_depth, skipping `skip` (the triangle the
// ray leaves, when the caller knows it); the list is sorted, so the walk stops at the first.
// The hit's t is the element's depth; the caller makes it a distance and places the point.
BOUNCE_HD inline LhbHit lhb_first_beyond(const LhbElement* list, int count, float min_depth,
                                         uint32_t skip) {
  for (int i = 0; i < count; ++i)
    if (list[i].depth > min_depth && list[i].prim != skip) {
      LhbHit h;
      h.prim = list[i].prim;
      h.t = list[i].depth;
      return h;
    }
  return {};
}

// An instance's answer for world point `o` (already jittered) along world direction `d`, buffer
// `direction`, replacing `best` when nearer. In the mesh's own space the ray runs along
// w = inverse * d; it first goes to where it enters the mesh's box, then along the instance's
// nearest direction to w (w itself when the mesh only translates), so that the gap between the
// two directions only counts from the box on, not from wherever the ray started. The hit comes
// back to the world as a point and a distance along d.
BOUNCE_HD inline void lhb_closest_instance(const LhbInstanceView& inst, int direction, vec3 o,
                                           vec3 d, float tmin, uint32_t skip, LhbHit& best) {
  const vec3 po = inst.inverse * (o - inst.offset);
  const vec3 w = inst.inverse * d;
  // Slab test against the box: [enter, leave] in units of w (world distances along d).
  float enter = tmin, leave = best.t;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / w[a];
    float s0 = (inst.box_lo[a] - po[a]) * inv, s1 = (inst.box_hi[a] - po[a]) * inv;
    if (s0 > s1) {
      const float swap = s0;
      s0 = s1;
      s1 = swap;
    }
    // NaN (a zero component with the origin on a face) leaves the bounds as they are.
    enter = s0 > enter ? s0 : enter;
    leave = s1 < leave ? s1 : leave;
  }
  if (!(enter <= leave)) return;
  const int j = inst.direction_of[direction];
  const LhbFrame& f = inst.frames[j];
  const vec3 start = po + enter * w;
  const vec2 xy = f.texel_coords(start);
  const float fx = std::floor(xy.x), fy = std::floor(xy.y);
  if (!(fx >= 0.0f && fy >= 0.0f && fx < float(inst.size) && fy < float(inst.size))) return;
  const size_t texel = inst.texel(j, int(fx), int(fy));
  const float z = f.depth(start);
  const LhbHit h = lhb_first_beyond(inst.slab.list(texel), inst.slab.kept(texel), z, skip);
  if (!h.valid()) return;
  const vec3 p = inst.linear * (start + (h.t - z) * f.d) + inst.offset;
  const float t = glm::dot(p - o, d);
  if (!(t < best.t)) return;
  best.prim = h.prim;
  best.t = t;
  best.point = p;
}

// Closest hit from `origin` along buffer `direction`: elements with depth > depth(origin) + tmin,
// in the static and moving slabs and every instance. `jitter` shifts the projected position by
// that many texels (0 for the exact ray). The returned t is the distance along the direction from
// the jittered origin, and point the hit on that line.
BOUNCE_HD inline LhbHit lhb_closest(const LhbView& view, int direction, vec3 origin, float tmin,
                                    vec2 jitter = vec2(0.0f), uint32_t skip = LhbHit::kNone) {
  const LhbFrame& f = view.frames[direction];
  const vec3 o = origin + f.across(jitter);
  LhbHit best;
  const vec2 xy = f.texel_coords(origin) + jitter;
  const float fx = std::floor(xy.x), fy = std::floor(xy.y);
  if (fx >= 0.0f && fy >= 0.0f && fx < float(view.size) && fy < float(view.size)) {
    const size_t texel = view.texel(direction, int(fx), int(fy));
    const float z = f.depth(origin);
    best = lhb_first_beyond(view.static_slab.list(texel), view.static_slab.kept(texel), z + tmin,
                            skip);
    if (!view.dynamic_slab.empty()) {
      const LhbHit moving = lhb_first_beyond(view.dynamic_slab.list(texel),
                                             view.dynamic_slab.kept(texel), z + tmin, skip);
      if (moving.t < best.t) best = moving;
    }
    if (best.valid()) {
      best.t -= z;
      best.point = o + best.t * f.d;
    }
  }
  for (int i = 0; i < view.instance_count; ++i)
    lhb_closest_instance(view.instances[i], direction, o, f.d, tmin, skip, best);
  return best;
}

}  // namespace bounce
