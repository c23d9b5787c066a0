// The deep rasterizer's bodies (seed 001, section 4): a triangle into one direction's layered hit
// buffer. Every texel centre the projected triangle covers gets the element {depth of the
// triangle's plane at that centre, triangle id}, inserted in depth order.
//
// - Coverage is tested at texel centres on barycentrics, with a small tolerance so that a centre
//   on an edge shared by two triangles records both: a ray along the direction through a texel
//   centre finds every triangle it would hit (conservative, not a fill rule that picks one).
// - Small triangles (bounding box under kLhbMacroArea texels, the seed's warp-sized cut-off)
//   test every texel of their box. Larger ones are split into 8 x 8 texel blocks classified by
//   their corner centres: blocks some edge excludes entirely are skipped, blocks inside all edges
//   are filled without tests, the rest tested per texel (the seed's block half-space variant,
//   without its flaw: a block is rejected only when one edge excludes all four corners).
// - A full texel keeps its `layers` nearest elements and counts what it drops (the seed drops
//   the latest arrivals, which depends on thread timing; the nearest are what a query from the
//   front of the scene needs, and the result does not depend on the order of arrival).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/scene/mesh.h"
#include "bounce/techniques/lhb/lhb_view.h"
#include "bounce/trace/cutout_view.h"

namespace bounce {

inline constexpr float kLhbMacroArea = 32.0f;      // texels; seed 001 section 4.3
inline constexpr int kLhbBlock = 8;                // side of the blocks large triangles split into
inline constexpr float kLhbEdgeTolerance = 1e-5f;  // barycentric slack at edges

// One direction's part of a slab, writable: texels [0, size*size) of that direction.
struct LhbSlabOut {
  LhbElement* elements = nullptr;
  uint8_t* counts = nullptr;
  int layers = 0;
};

struct LhbRasterStats {
  uint64_t arrived = 0;  // elements rasterized
  uint64_t dropped = 0;  // elements a full texel did not keep
};

// Inserts e into a texel's depth-sorted list; a full list keeps the nearest `layers`.
BOUNCE_HD inline void lhb_insert(LhbElement* list, uint8_t& count, int layers, LhbElement e,
                                 LhbRasterStats& stats) {
  const int arrived = count;
  if (arrived < 255) count = uint8_t(arrived + 1);
  ++stats.arrived;
  int i = arrived < layers ? arrived : layers;
  if (i == layers) {
    ++stats.dropped;
    if (!(e.depth < list[layers - 1].depth)) return;  // the new one is the farthest: drop it
    i = layers - 1;                                   // else the farthest kept one goes
  }
  for (; i > 0 && list[i - 1].depth > e.depth; --i) list[i] = list[i - 1];
  list[i] = e;
}

// A plane over the texel grid: value at texel (x, y)'s centre = base + gx * x + gy * y.
struct LhbPlane {
  float base, gx, gy;
  BOUNCE_HD float at(int x, int y) const { return base + gx * float(x) + gy * float(y); }
};

// A vertex seen along a buffer's direction: texel coordinates and depth. Projected once per
// vertex and direction, shared by the triangles around it.
struct LhbProjected {
  vec2 texel;
  float depth;
};

BOUNCE_HD inline LhbProjected lhb_project(const LhbFrame& f, vec3 p) {
  return {f.texel_coords(p), f.depth(p)};
}

// The sign that turns a triangle's signed area in f's texel coordinates into the sign of
// dot(its normal, f.d): +1 when u x v = d, -1 when u x v = -d (the scales are positive).
BOUNCE_HD inline float lhb_area_to_facing(const LhbFrame& f) {
  return glm::dot(glm::cross(f.u, f.v), f.d) < 0.0f ? -1.0f : 1.0f;
}

// Rasterizes the projected triangle (a, b, c) with id `prim` into one direction's texels.
// With cull_back_faces only triangles a ray along the direction meets from the front are kept
// (the seed's rule: each direction answers rays travelling along it); `area_to_facing` comes from
// lhb_area_to_facing. Texel centres that fall in a hole of an alpha cut-out (`triangle` of scene
// mesh `mesh` in `cutouts`) record nothing, so rays through the buffers pass holes as traced rays
// do. The box of texel centres is found first: most triangles of a dense mesh cover no centre
// and leave before any other work.
BOUNCE_HD inline void lhb_raster_projected(int size, LhbProjected pa, LhbProjected pb,
                                           LhbProjected pc, float area_to_facing, uint32_t prim,
                                           bool cull_back_faces, const CutoutView& cutouts,
                                           uint32_t mesh, uint32_t triangle, const LhbSlabOut& out,
                                           LhbRasterStats& stats) {
  const vec2 a = pa.texel, b = pb.texel, c = pc.texel;
  // Texels whose centres (x + 0.5, y + 0.5) lie in the bounding box, slightly widened. Plain
  // comparisons, not fminf/fmaxf: those are library calls on the CPU (NaN rules), and this test
  // is most of the work for a dense mesh.
  const auto lo3 = [](float p, float q, float r) {
    const float m = p < q ? p : q;
    return m < r ? m : r;
  };
  const auto hi3 = [](float p, float q, float r) {
    const float m = p > q ? p : q;
    return m > r ? m : r;
  };
  const float slack = 1e-3f;
  const float lo_x = std::ceil(lo3(a.x, b.x, c.x) - 0.5f - slack);
  const float hi_x = std::floor(hi3(a.x, b.x, c.x) - 0.5f + slack);
  const float lo_y = std::ceil(lo3(a.y, b.y, c.y) - 0.5f - slack);
  const float hi_y = std::floor(hi3(a.y, b.y, c.y) - 0.5f + slack);
  // Also false for NaN coordinates.
  if (!(lo_x <= hi_x && lo_y <= hi_y && hi_x >= 0.0f && hi_y >= 0.0f && lo_x <= float(size - 1) &&
        lo_y <= float(size - 1)))
    return;
  const int x0 = lo_x > 0.0f ? int(lo_x) : 0, y0 = lo_y > 0.0f ? int(lo_y) : 0;
  const int x1 = hi_x < float(size - 1) ? int(hi_x) : size - 1;
  const int y1 = hi_y < float(size - 1) ? int(hi_y) : size - 1;
  const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  const float facing = area * area_to_facing;
  if (cull_back_faces ? !(facing < 0.0f) : !(facing != 0.0f)) return;
  if (!std::isfinite(area)) return;
  const float za = pa.depth, zb = pb.depth, zc = pc.depth;

  // Barycentrics of vertices 1 and 2 and the depth, as planes over texel indices.
  const float inv = 1.0f / area;
  const float cx = float(x0) + 0.5f - a.x, cy = float(y0) + 0.5f - a.y;
  const LhbPlane l1{(cx * (c.y - a.y) - cy * (c.x - a.x)) * inv, (c.y - a.y) * inv,
                    -(c.x - a.x) * inv};
  const LhbPlane l2{(cy * (b.x - a.x) - cx * (b.y - a.y)) * inv, -(b.y - a.y) * inv,
                    (b.x - a.x) * inv};
  const LhbPlane depth{za + l1.base * (zb - za) + l2.base * (zc - za),
                       l1.gx * (zb - za) + l2.gx * (zc - za),
                       l1.gy * (zb - za) + l2.gy * (zc - za)};
  // Texel (x, y) of the slab is at index y * size + x; the planes count from (x0, y0).
  const bool alpha_tested = cutouts.mesh_count > 0;
  auto emit = [&](int x, int y) {
    if (alpha_tested &&
        cutouts.passes(mesh, triangle, l1.at(x - x0, y - y0), l2.at(x - x0, y - y0)))
      return;
    const size_t texel = size_t(y) * size_t(size) + size_t(x);
    lhb_insert(out.elements + texel * size_t(out.layers), out.counts[texel], out.layers,
               {depth.at(x - x0, y - y0), prim}, stats);
  };
  auto covered = [&](int i, int j) {
    const float w1 = l1.at(i, j), w2 = l2.at(i, j);
    return w1 >= -kLhbEdgeTolerance && w2 >= -kLhbEdgeTolerance &&
           1.0f - w1 - w2 >= -kLhbEdgeTolerance;
  };

  if (float(x1 - x0 + 1) * float(y1 - y0 + 1) < kLhbMacroArea) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (covered(x - x0, y - y0)) emit(x, y);
    return;
  }
  for (int by = y0; by <= y1; by += kLhbBlock)
    for (int bx = x0; bx <= x1; bx += kLhbBlock) {
      const int ex = bx + kLhbBlock - 1 < x1 ? bx + kLhbBlock - 1 : x1;
      const int ey = by + kLhbBlock - 1 < y1 ? by + kLhbBlock - 1 : y1;
      // The three barycentrics at the block's corner centres: linear, so their extremes are
      // the corners' extremes.
      bool outside = false, inside = true;
      const int cxs[2] = {bx - x0, ex - x0}, cys[2] = {by - y0, ey - y0};
      for (int k = 0; k < 3; ++k) {
        float lo = 1e30f, hi = -1e30f;
        for (int q = 0; q < 4; ++q) {
          const int i = cxs[q & 1], j = cys[q >> 1];
          const float w1 = l1.at(i, j), w2 = l2.at(i, j);
          const float w = k == 0 ? w1 : k == 1 ? w2 : 1.0f - w1 - w2;
          lo = fminf(lo, w);
          hi = fmaxf(hi, w);
        }
        outside |= hi < -kLhbEdgeTolerance;
        inside &= lo >= -kLhbEdgeTolerance;
      }
      if (outside) continue;
      for (int y = by; y <= ey; ++y)
        for (int x = bx; x <= ex; ++x)
          if (inside || covered(x - x0, y - y0)) emit(x, y);
    }
}

// Rasterizes triangle (p0, p1, p2) into direction frame f (see lhb_raster_projected): one
// triangle and one direction on its own, as a GPU thread would take them.
BOUNCE_HD inline void lhb_raster_triangle(const LhbFrame& f, int size, vec3 p0, vec3 p1, vec3 p2,
                                          uint32_t prim, bool cull_back_faces,
                                          const CutoutView& cutouts, uint32_t mesh,
                                          uint32_t triangle, const LhbSlabOut& out,
                                          LhbRasterStats& stats) {
  lhb_raster_projected(size, lhb_project(f, p0), lhb_project(f, p1), lhb_project(f, p2),
                       lhb_area_to_facing(f), prim, cull_back_faces, cutouts, mesh, triangle, out,
                       stats);
}

// Every triangle of scene mesh `mesh_index` into one direction; triangle ids start at
// first_prim. `projected` is scratch of mesh.vertex_count entries: each vertex is projected
// once, not once per triangle around it.
BOUNCE_HD inline void lhb_raster_mesh(const LhbFrame& f, int size, const MeshView& mesh,
                                      uint32_t mesh_index, uint32_t first_prim,
                                      bool cull_back_faces, const CutoutView& cutouts,
                                      LhbProjected* projected, const LhbSlabOut& out,
                                      LhbRasterStats& stats) {
  for (uint32_t v = 0; v < mesh.vertex_count; ++v) projected[v] = lhb_project(f, mesh.positions[v]);
  const float area_to_facing = lhb_area_to_facing(f);
  for (uint32_t t = 0; t < mesh.triangle_count; ++t) {
    const uvec3 i = mesh.triangles[t];
    lhb_raster_projected(size, projected[i.x], projected[i.y], projected[i.z], area_to_facing,
                         first_prim + t, cull_back_faces, cutouts, mesh_index, t, out, stats);
  }
}

}  // namespace bounce
