// Plain data of the layered hit buffers (seed 001, section 1.6): what the deep rasterizer writes
// and the ray query reads, as pointers and sizes that a kernel (CPU or GPU) can take by value.
//
// One buffer per direction d: an orthographic size x size grid over the scene seen along d. Each
// texel is one ray parallel to d through the texel centre; it holds the surfaces that ray crosses
// as elements {depth along d, global triangle id}, sorted by depth, at most `layers` of them.
// Two slabs share that layout: the static part of the scene (built once) and the meshes that move
// (rebuilt every frame); a query reads both (the seed's two counter sets, kept apart here so the
// static slab is never copied). Large moving meshes are instances instead: buffers of their own,
// built once in their own frame, that a query enters through the mesh's current transform.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Where buffer d lies in the world: texel coordinates x = (dot(p, u) - u0) * scale_u (and y from
// v), depth = dot(p, d). u, v, d are orthonormal.
struct LhbFrame {
  vec3 u, v, d;
  float u0, v0;
  float scale_u, scale_v;  // texels per world unit

  BOUNCE_HD vec2 texel_coords(vec3 p) const {
    return {(glm::dot(p, u) - u0) * scale_u, (glm::dot(p, v) - v0) * scale_v};
  }
  BOUNCE_HD float depth(vec3 p) const { return glm::dot(p, d); }
  // The world offset, across the direction, of a shift of (dx, dy) texels.
  BOUNCE_HD vec3 across(vec2 texels) const {
    return (texels.x / scale_u) * u + (texels.y / scale_v) * v;
  }
};

struct LhbElement {
  float depth;    // along the buffer's direction (LhbFrame::depth of the hit point)
  uint32_t prim;  // global triangle id (Scene::triangle_offsets numbering)
};

// One slab: `layers` elements per texel, texels of all directions one after the other.
// counts[texel] is how many elements arrived there, saturating at 255: the texel holds the
// min(count, layers) nearest ones, and a count above `layers` says it overflowed.
struct LhbSlabView {
  const LhbElement* elements = nullptr;
  const uint8_t* counts = nullptr;
  int layers = 0;

  BOUNCE_HD bool empty() const { return elements == nullptr; }
  BOUNCE_HD int kept(size_t texel) const {
    const int c = counts[texel];
    return c < layers ? c : layers;
  }
  BOUNCE_HD const LhbElement* list(size_t texel) const { return elements + texel * size_t(layers); }
};

// Texel (x, y) of buffer `direction` in a slab of size x size texels per direction.
BOUNCE_HD inline size_t lhb_texel_index(int direction, int size, int x, int y) {
  return (size_t(direction) * size_t(size) + size_t(y)) * size_t(size) + size_t(x);
}

// A moving mesh whose motion is affine (every motion this engine's animation and edits make):
// its buffers are built once in the pose it had then, its "object space", and re-posed by a
// transform each frame instead of rasterized again. world = linear * object + offset.
struct LhbInstanceView {
  mat3 linear{1.0f}, inverse{1.0f};
  vec3 offset{0.0f};
  vec3 box_lo{0.0f}, box_hi{0.0f};         // the mesh's box in its own space, a texel wider
  const LhbFrame* frames = nullptr;        // one per direction, over the mesh's own box
  const uint16_t* direction_of = nullptr;  // world direction -> nearest object-space direction
  int size = 0;                            // texels per side
  LhbSlabView slab;

  BOUNCE_HD size_t texel(int direction, int x, int y) const {
    return lhb_texel_index(direction, size, x, y);
  }
};

struct LhbView {
  const LhbFrame* frames = nullptr;
  int direction_count = 0;
  int size = 0;  // texels per side
  LhbSlabView static_slab;
  LhbSlabView dynamic_slab;  // empty when no mesh moves, or when every moving mesh is an instance
  const LhbInstanceView* instances = nullptr;
  int instance_count = 0;

  BOUNCE_HD size_t texel(int direction, int x, int y) const {
    return lhb_texel_index(direction, size, x, y);
  }
};

static_assert(std::is_trivially_copyable_v<LhbFrame>);
static_assert(std::is_trivially_copyable_v<LhbElement>);
static_assert(std::is_trivially_copyable_v<LhbInstanceView>);
static_assert(std::is_trivially_copyable_v<LhbView>);

}  // namespace bounce
