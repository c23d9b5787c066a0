// Ray queries against our own BVH (bvh_view.h), written once for the host and the device: a
// fixed-size stack, the nearer child first, no recursion, containers or exceptions.
// Semantics are Embree's as our tracer uses it: both faces hit, a hit counts when
// ray.tmin < t <= ray.tmax, the hit names the mesh and the triangle within it, and its
// barycentric holds the weights of vertices 1 and 2, and a hit in an alpha cut-out's hole does not
// count (cutout_view.h: the test Embree's filter makes too).
//
// Triangles use the watertight test of Woop, Benthin and Wald (2013): vertices are moved into a
// space where the ray runs along +z from the origin, and the three edge functions decide the hit.
// The shear and the edge functions are evaluated in double: a product of two floats is exact
// there, so the two triangles sharing an edge compute exactly opposite values for it whatever the
// compiler fuses into FMAs (host and device, every caller alike), and a ray through the edge
// cannot slip between them. Box tests widen the exit
// distance by 2 gamma(3) (Ize 2013) so that rounding cannot cull a box the ray touches, flat boxes
// of axis-aligned faces included.
#pragma once

#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/trace/bvh_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

namespace bvh_detail {

// Deep enough for any tree the builder makes: it stops using SAH splits beyond depth 32 and
// halves the triangle count from there on (bvh.cpp), and the traversal pushes one node per level.
constexpr int kStackSize = 64;

BOUNCE_HD inline float min_f(float a, float b) {
  return a < b ? a : b;
}
BOUNCE_HD inline float max_f(float a, float b) {
  return a > b ? a : b;
}
BOUNCE_HD inline float abs_f(float a) {
  return a < 0.0f ? -a : a;
}
// Component k of (x, y, z), by selects (a dynamically indexed array would live in GPU local
// memory).
BOUNCE_HD inline float pick(float x, float y, float z, int k) {
  return k == 0 ? x : (k == 1 ? y : z);
}

// What the traversal precomputes once per ray.
struct BvhRay {
  float org[3];
  float inv[3];    // 1 / direction, a zero component replaced by a tiny one (no 0 * inf)
  bool neg[3];     // per axis, whether the ray enters a box through its high plane
  int kx, ky, kz;  // the watertight test's axes: kz the direction's largest component
  float sx, sy, sz;
};

BOUNCE_HD inline BvhRay make_bvh_ray(const Ray& ray) {
  BvhRay r;
  const float d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  r.org[0] = ray.origin.x;
  r.org[1] = ray.origin.y;
  r.org[2] = ray.origin.z;
  for (int k = 0; k < 3; ++k) {
    const float dk = abs_f(d[k]) > 1e-30f ? d[k] : (d[k] < 0.0f ? -1e-30f : 1e-30f);
    r.inv[k] = 1.0f / dk;
    r.neg[k] = r.inv[k] < 0.0f;
  }
  const float ax = abs_f(d[0]), ay = abs_f(d[1]), az = abs_f(d[2]);
  r.kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  const float dz = d[r.kz];
  if (dz < 0.0f) {  // keep the winding, so the edge functions' signs mean the same
    const int swap = r.kx;
    r.kx = r.ky;
    r.ky = swap;
  }
  r.sx = d[r.kx] / dz;
  r.sy = d[r.ky] / dz;
  r.sz = 1.0f / dz;
  return r;
}

// p - s * z, the same in every caller: the product is exact in double, so whether the compiler
// fuses it into an FMA changes nothing, and the one rounding to float is the same everywhere.
BOUNCE_HD inline float shear(float p, float s, float z) {
  return float(double(p) - double(s) * double(z));
}

// Whether the ray enters the box within [tmin, tmax]; `entry` is where it does. The planes are
// picked by selects, not indices: a node copied into registers stays there (an indexed array
// would live in GPU local memory).
BOUNCE_HD inline bool hit_box(const BvhRay& r, const float* box, float tmin, float tmax,
                              float& entry) {
  const float x0 = ((r.neg[0] ? box[3] : box[0]) - r.org[0]) * r.inv[0];
  const float y0 = ((r.neg[1] ? box[4] : box[1]) - r.org[1]) * r.inv[1];
  const float z0 = ((r.neg[2] ? box[5] : box[2]) - r.org[2]) * r.inv[2];
  const float x1 = ((r.neg[0] ? box[0] : box[3]) - r.org[0]) * r.inv[0];
  const float y1 = ((r.neg[1] ? box[1] : box[4]) - r.org[1]) * r.inv[1];
  const float z1 = ((r.neg[2] ? box[2] : box[5]) - r.org[2]) * r.inv[2];
  entry = max_f(max_f(x0, y0), max_f(z0, tmin));
  const float exit = min_f(min_f(min_f(x1, y1), z1) * 1.0000004f, tmax);
  return entry <= exit;
}

// The watertight ray/triangle test; on a hit within (tmin, tmax] sets t and the weights (u, v)
// of vertices 1 and 2.
BOUNCE_HD inline bool hit_triangle(const BvhRay& r, const BvhTriangle& tri, float tmin, float tmax,
                                   float& t, float& u, float& v) {
  // Vertices relative to the origin, sheared so that the ray runs along +z.
  const float a0 = tri.v0.x - r.org[0], a1 = tri.v0.y - r.org[1], a2 = tri.v0.z - r.org[2];
  const float b0 = tri.v1.x - r.org[0], b1 = tri.v1.y - r.org[1], b2 = tri.v1.z - r.org[2];
  const float c0 = tri.v2.x - r.org[0], c1 = tri.v2.y - r.org[1], c2 = tri.v2.z - r.org[2];
  const float az = pick(a0, a1, a2, r.kz), bz = pick(b0, b1, b2, r.kz), cz = pick(c0, c1, c2, r.kz);
  const float ax = shear(pick(a0, a1, a2, r.kx), r.sx, az);
  const float ay = shear(pick(a0, a1, a2, r.ky), r.sy, az);
  const float bx = shear(pick(b0, b1, b2, r.kx), r.sx, bz);
  const float by = shear(pick(b0, b1, b2, r.ky), r.sy, bz);
  const float cx = shear(pick(c0, c1, c2, r.kx), r.sx, cz);
  const float cy = shear(pick(c0, c1, c2, r.ky), r.sy, cz);
  // Edge functions: each one's sign says on which side of an edge the ray passes.
  const double eu = double(cx) * double(by) - double(cy) * double(bx);
  const double ev = double(ax) * double(cy) - double(ay) * double(cx);
  const double ew = double(bx) * double(ay) - double(by) * double(ax);
  if ((eu < 0.0 || ev < 0.0 || ew < 0.0) && (eu > 0.0 || ev > 0.0 || ew > 0.0)) return false;
  const double det = eu + ev + ew;
  if (det == 0.0) return false;  // the ray lies in the triangle's plane
  // The distance and weights in double as well: rounded once to float at the end, they come out
  // the same however the compiler schedules them in each caller.
  const double inv_det = 1.0 / det;
  t = float((eu * double(az) + ev * double(bz) + ew * double(cz)) * double(r.sz) * inv_det);
  if (!(t > tmin && t <= tmax)) return false;
  u = float(ev * inv_det);
  v = float(ew * inv_det);
  return true;
}

#if BOUNCE_DEVICE_CODE
// A node and a triangle as the GPU reads them: in 16-byte loads through the read-only data cache
// (both are 16-byte aligned and never written while rays run), into registers. The CPU reads
// them in place: copying each node cost it 3-13% of its rate.
__device__ inline BvhNode load_node(const BvhNode* nodes, uint32_t i) {
  const float4* p = reinterpret_cast<const float4*>(nodes + i);
  const float4 a = __ldg(p), b = __ldg(p + 1), c = __ldg(p + 2);
  const uint4 d = __ldg(reinterpret_cast<const uint4*>(p + 3));
  BvhNode n;
  n.box[0][0] = a.x, n.box[0][1] = a.y, n.box[0][2] = a.z, n.box[0][3] = a.w;
  n.box[0][4] = b.x, n.box[0][5] = b.y, n.box[1][0] = b.z, n.box[1][1] = b.w;
  n.box[1][2] = c.x, n.box[1][3] = c.y, n.box[1][4] = c.z, n.box[1][5] = c.w;
  n.child[0] = d.x, n.child[1] = d.y, n.count[0] = d.z, n.count[1] = d.w;
  return n;
}
__device__ inline BvhTriangle load_triangle(const BvhTriangle* triangles, uint32_t k) {
  const float4* p = reinterpret_cast<const float4*>(triangles + k);
  const float4 a = __ldg(p), b = __ldg(p + 1), c = __ldg(p + 2);
  return {vec4(a.x, a.y, a.z, a.w), vec4(b.x, b.y, b.z, b.w), vec4(c.x, c.y, c.z, c.w)};
}
#else
inline const BvhNode& load_node(const BvhNode* nodes, uint32_t i) {
  return nodes[i];
}
inline const BvhTriangle& load_triangle(const BvhTriangle* triangles, uint32_t k) {
  return triangles[k];
}
#endif

// Walks the tree. kAnyHit: returns at the first hit in range. Otherwise fills `hit` with the
// closest and returns whether there was one. (Written as a resumable walk of one node per step,
// the same traversal traced random rays through cubes:10000 22% faster on an H100, but shadow rays
// 14% slower, and a 1080p frame's G-buffer 37% slower: not taken.)
template <bool kAnyHit>
BOUNCE_HD inline bool traverse(const BvhView& bvh, const Ray& ray, Hit& hit) {
  if (bvh.node_count == 0) return false;
  const BvhRay r = make_bvh_ray(ray);
  float tmax = ray.tmax;
  uint32_t best = Hit::kNone;
  float best_u = 0.0f, best_v = 0.0f;
  uint32_t stack[kStackSize];
  int depth = 0;
  uint32_t node = 0;
  for (;;) {
    const auto& n = load_node(bvh.nodes, node);  // a copy on the GPU, in place on the CPU
    float entry0, entry1;
    const bool in0 = hit_box(r, n.box[0], ray.tmin, tmax, entry0);
    const bool in1 = hit_box(r, n.box[1], ray.tmin, tmax, entry1);
    const bool second_first = in1 && (!in0 || entry1 < entry0);
    uint32_t next = Hit::kNone;
    for (int i = 0; i < 2; ++i) {
      // Child c, the nearer first, by selects (see hit_box).
      const bool c1 = (i == 0) == second_first;
      const float entry = c1 ? entry1 : entry0;
      if (!(c1 ? in1 : in0) || entry > tmax) continue;  // a leaf may have moved tmax
      const uint32_t child = c1 ? n.child[1] : n.child[0];
      if (child & BvhNode::kLeaf) {
        const uint32_t begin = child & ~BvhNode::kLeaf,
                       end = begin + (c1 ? n.count[1] : n.count[0]);
        for (uint32_t k = begin; k < end; ++k) {
          float t, u, v;
          if (!hit_triangle(r, load_triangle(bvh.triangles, k), ray.tmin, tmax, t, u, v)) continue;
          if (bvh.cutouts.mesh_count > 0 &&
              bvh.cutouts.passes(bvh.ids[k].mesh, bvh.ids[k].triangle, u, v))
            continue;  // a hole in an alpha-masked material
          if constexpr (kAnyHit) return true;
          tmax = t;
          best = k;
          best_u = u;
          best_v = v;
        }
      } else if (next == Hit::kNone) {
        next = child;
      } else {
        stack[depth++] = child;  // the farther inner child waits
      }
    }
    if (next != Hit::kNone) {
      node = next;
    } else if (depth > 0) {
      node = stack[--depth];
    } else {
      break;
    }
  }
  if (best == Hit::kNone) return false;
  hit.t = tmax;
  hit.mesh = bvh.ids[best].mesh;
  hit.triangle = bvh.ids[best].triangle;
  hit.barycentric = vec2(best_u, best_v);
  return true;
}

}  // namespace bvh_detail

// The closest triangle on the ray within (tmin, tmax], or no hit.
BOUNCE_HD inline Hit bvh_intersect(const BvhView& bvh, const Ray& ray) {
  Hit hit;
  bvh_detail::traverse<false>(bvh, ray, hit);
  return hit;
}

// Whether any triangle lies on the ray within (tmin, tmax].
BOUNCE_HD inline bool bvh_occluded(const BvhView& bvh, const Ray& ray) {
  Hit unused;
  return bvh_detail::traverse<true>(bvh, ray, unused);
}

}  // namespace bounce
