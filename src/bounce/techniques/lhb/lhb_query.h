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
// w = inverse * d, which the instance's nearest direction f.d only approximates when the mesh
// has turned. So the ray enters the mesh's box and then walks the texels of f's grid that it
// crosses: in each texel, between the depths (along f.d) where it comes in and goes out, the
// first element is its hit (within a texel's depth of either end: elements sit at texel
// centres). For a mesh that only translated, w is f.d and the walk is one texel, the same list
// walk as the scene's buffers. The hit comes back to the world as a point on the ray and a
// distance along d.
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
  // Per unit of depth along f.d the ray moves this many texels across (0 when w is f.d).
  const float depth_rate = glm::dot(w, f.d);  // depth per world unit along d
  if (!(depth_rate > 0.0f)) return;
  const vec2 across(glm::dot(w, f.u) * f.scale_u / depth_rate,
                    glm::dot(w, f.v) * f.scale_v / depth_rate);
  const vec2 xy0 = f.texel_coords(start);
  const float z0 = f.depth(start), z_end = z0 + (leave - enter) * depth_rate;
  // A texel's depth: how far an element at its centre may lie from the surface under the ray.
  const float slack = 1.0f / (f.scale_u < f.scale_v ? f.scale_u : f.scale_v);
  float fx = std::floor(xy0.x), fy = std::floor(xy0.y);
  float z_in = z0;
  for (int step = 0; step <= 2 * inst.size + 1; ++step) {
    if (!(fx >= 0.0f && fy >= 0.0f && fx < float(inst.size) && fy < float(inst.size))) return;
    // Where the ray leaves this texel: the nearer of its x and y exits (or the box's end).
    float z_out = z_end, zx = z_end, zy = z_end;
    if (across.x > 0.0f) zx = z0 + (fx + 1.0f - xy0.x) / across.x;
    if (across.x < 0.0f) zx = z0 + (fx - xy0.x) / across.x;
    if (across.y > 0.0f) zy = z0 + (fy + 1.0f - xy0.y) / across.y;
    if (across.y < 0.0f) zy = z0 + (fy - xy0.y) / across.y;
    z_out = zx < z_out ? zx : z_out;
    z_out = zy < z_out ? zy : z_out;
    const size_t texel = inst.texel(j, int(fx), int(fy));
    const LhbElement* list = inst.slab.list(texel);
    const int count = inst.slab.kept(texel);
    const float lo = step == 0 ? z0 : z_in - slack, hi = z_out + slack;
    for (int i = 0; i < count; ++i) {
      const LhbElement e = list[i];
      if (!(e.depth > lo) || !(e.depth > z0) || e.prim == skip) continue;
      if (e.depth > hi && z_out < z_end) break;  // beyond this texel: a later one holds it
      // On the ray where its depth is the element's.
      const vec3 p = inst.linear * (start + ((e.depth - z0) / depth_rate) * w) + inst.offset;
      const float t = glm::dot(p - o, d);
      if (t < best.t) {
        best.prim = e.prim;
        best.t = t;
        best.point = p;
      }
      return;
    }
    if (!(z_out < z_end)) return;
    z_in = z_out;
    if (zx <= zy)
      fx += across.x > 0.0f ? 1.0f : -1.0f;
    else
      fy += across.y > 0.0f ? 1.0f : -1.0f;
  }
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
