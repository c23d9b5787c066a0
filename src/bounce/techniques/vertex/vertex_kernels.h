// Kernel bodies of the vertex technique's per-pixel and per-vertex work (README.md "A frame"):
// each pixel finds its refined triangle and marks the estimates it needs; each needed estimate is
// made once; each pixel interpolates its triangle's three (Gouraud shading, seed §3.3).
#pragma once

#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/scene/scene_view.h"
#include "bounce/techniques/vertex/photon_kdtree.h"
#include "bounce/techniques/vertex/refined_mesh.h"
#include "bounce/techniques/vertex/vertex_estimate.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

inline constexpr uint32_t kNoLeaf = 0xFFFFFFFFu;

// Sets a flag that many threads may set at once (all to 1).
BOUNCE_HD inline void set_flag(uint8_t* flag) {
#if BOUNCE_DEVICE_CODE
  *flag = 1;
#else
  __atomic_store_n(flag, uint8_t(1), __ATOMIC_RELAXED);
#endif
}

// An estimate's slot: per key (the estimate cache) or per refined triangle corner, and side (0:
// the side the coarse triangle's winding faces, 1: the other).
BOUNCE_HD inline uint32_t estimate_slot_of(const RefinedMeshView& m, bool per_key, uint32_t leaf,
                                           int corner, int side) {
  return per_key ? m.leaf_keys[leaf][corner] * 2u + uint32_t(side)
                 : (leaf * 3u + uint32_t(corner)) * 2u + uint32_t(side);
}

struct VertexPixelView {
  ConstGBufferView g;
  SceneView scene;
  RefinedMeshView mesh;
  uint32_t* leaf;  // per pixel, kNoLeaf where nothing needs light
  vec3* weights;
  uint8_t* side;
  uint8_t* needed;  // per estimate slot
  bool per_key;
};
static_assert(std::is_trivially_copyable_v<VertexPixelView>);

// What locate_pixel keeps from one pixel to the next of a run (the CPU's; a GPU thread starts
// each pixel afresh): neighbouring pixels mostly lie on one refined triangle of one coarse
// triangle, seen from the same side.
struct LocateHint {
  uint32_t leaf = kNoHint;    // the refined triangle found last (locate_refined's hint)
  int side = -1;              // the side its estimates were flagged for
  uint32_t coarse = kNoHint;  // the coarse triangle whose face normal `face` is
  vec3 face{0.0f};
};

// Pixel i's refined triangle, weights and side, and the estimates it needs flagged, starting
// from what the pixel before left in `hint`.
BOUNCE_HD inline void locate_pixel(const VertexPixelView& v, size_t i, LocateHint& hint) {
  v.leaf[i] = kNoLeaf;
  if (!v.g.hit(i) || !(max_component(v.g.albedo[i]) > 0.0f)) return;
  const uint32_t coarse = v.g.primitive[i];
  const RefinedPoint p = locate_refined(v.mesh, coarse, v.g.barycentric[i], hint.leaf);
  if (coarse != hint.coarse) {
    const uint32_t m = v.g.mesh[i];
    hint.face = v.scene.meshes[m].face_normal_area2(coarse - v.scene.triangle_offsets[m]);
    hint.coarse = coarse;
  }
  const int side = glm::dot(v.g.geometric_normal[i], hint.face) >= 0.0f ? 0 : 1;
  v.leaf[i] = p.leaf;
  v.weights[i] = p.weights;
  v.side[i] = uint8_t(side);
  if (p.leaf != hint.leaf || side != hint.side)
    for (int k = 0; k < 3; ++k)
      set_flag(v.needed + estimate_slot_of(v.mesh, v.per_key, p.leaf, k, side));
  hint.leaf = p.leaf;
  hint.side = side;
}
BOUNCE_HD inline void locate_pixel(const VertexPixelView& v, size_t i) {
  LocateHint fresh;
  locate_pixel(v, i, fresh);
}

struct VertexEstimateView {
  RefinedMeshView mesh;
  PhotonMapView tree;  // the lights that stay put, then those that move
  SceneView scene;
  TraceView trace;
  EstimateSettings settings;
  vec3* irradiance;  // per estimate slot
  bool per_key;
};
static_assert(std::is_trivially_copyable_v<VertexEstimateView>);

// The irradiance of one slot: at its key, on its side.
BOUNCE_HD inline void estimate_slot(const VertexEstimateView& v, uint32_t slot) {
  const int side = int(slot & 1u);
  const uint32_t key = v.per_key ? slot / 2u : v.mesh.leaf_keys[slot / 6u][int((slot / 2u) % 3u)];
  const vec3 x = v.mesh.key_position[key];
  const vec3 n = side == 0 ? v.mesh.key_normal[key] : -v.mesh.key_normal[key];
  KnnHeap heap;
  v.irradiance[slot] =
      v.settings.final_gather_rays > 0
          ? final_gather_irradiance(v.scene, v.trace, v.tree, x, n, v.settings, key, heap)
          : photon_irradiance(v.tree, x, n, v.settings, heap);
}

// Indirect radiance at pixel i: albedo / pi times the irradiance interpolated over its triangle.
BOUNCE_HD inline vec3 interpolate_pixel(const VertexPixelView& v, const vec3* irradiance,
                                        size_t i) {
  const uint32_t leaf = v.leaf[i];
  if (leaf == kNoLeaf) return vec3(0.0f);
  const vec3 w = v.weights[i];
  const int side = v.side[i];
  vec3 e(0.0f);
  for (int k = 0; k < 3; ++k)
    e += w[k] * irradiance[estimate_slot_of(v.mesh, v.per_key, leaf, k, side)];
  return v.g.albedo[i] * (e * kInvPi);
}

}  // namespace bounce
