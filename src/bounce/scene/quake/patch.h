// Tessellation of Quake 3 curved surfaces: a face's control grid (width x height points, both
// odd) is a grid of biquadratic Bezier patches, each a 3 x 3 block sharing its border row or
// column with its neighbour. Each patch becomes level x level quads.
//
// Watertight by construction: a point on a patch border depends only on the three control points
// of that border, evaluated at the same parameter steps k / level, and the evaluation is exactly
// symmetric (a border walked backwards gives bit-identical points), so two patches that share a
// border, in one face or in two faces, produce identical vertices along it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/scene/quake/bsp.h"

namespace bounce::quake {

constexpr int kMaxPatchLevel = 64;

// The quadratic Bezier through a, b, c at parameter k / level, computed so that
// quadratic(a, b, c, k, n) == quadratic(c, b, a, n - k, n) exactly.
template <typename T>
BOUNCE_HD T bezier_step(const T& a, const T& b, const T& c, int k, int level) {
  const bool mirror = 2 * k > level;
  const float t = float(mirror ? level - k : k) / float(level);
  const float w0 = (1.0f - t) * (1.0f - t), w1 = 2.0f * t * (1.0f - t), w2 = t * t;
  const T& first = mirror ? c : a;
  const T& last = mirror ? a : c;
  return (w0 * first + w2 * last) + w1 * b;
}

struct PatchVertex {
  vec3 position{0.0f};  // Quake units
  vec3 normal{0.0f};    // unit, or zero where the control normals cancel
  vec2 uv{0.0f};
};

struct PatchMesh {
  std::vector<PatchVertex> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;  // wound like the map's own triangles
};

// Appends the tessellated face (controls: width * height points, row-major, width across) to
// `out`. level must be in [1, kMaxPatchLevel].
void tessellate_patch(std::span<const BspVertex> controls, int width, int height, int level,
                      PatchMesh& out);

}  // namespace bounce::quake
