// Recognises an affine motion of a mesh: the map that carries the positions a mesh had when its
// hit buffers were built to the positions it has now, when there is one. Every motion this
// engine makes (keyframed translation, rotation and scale, glTF node animation, the viewer's
// object moves) is affine per mesh, so a moving mesh's buffers can be re-posed by that map
// instead of rasterized again; a deforming mesh fails the check and is rebuilt.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "bounce/core/math.h"

namespace bounce {

struct Affine {
  mat3 linear{1.0f};
  vec3 offset{0.0f};
  vec3 operator()(vec3 p) const { return linear * p + offset; }
};

// Four vertices of the first pose that pin an affine map down: p0, the farthest vertex from it,
// the farthest from their line, the farthest from their plane. A flat mesh (every vertex within
// a hair of one plane) has no fourth: the plane's normal, scaled like a length, stands in.
struct AffineAnchors {
  uint32_t index[4] = {0, 0, 0, 0};
  bool flat = false;
  mat3 edges_inverse{1.0f};  // inverse of the first pose's three edge vectors (columns)
  float extent = 0.0f;       // the first pose's bounding-box diagonal

  // Anchors for `rest`; nullopt when its vertices lie on a line or a point (no map is
  // determined, and such a mesh covers no texel anyway).
  static std::optional<AffineAnchors> choose(std::span<const vec3> rest);
};

// The map with map(rest[i]) == now[i] for every vertex, each within `tolerance` times the
// extent of the rest pose (times the map's stretch, when it grows the mesh), plus float
// rounding at the vertex's distance from the origin; nullopt when there is none (the mesh
// deformed) or the sizes differ.
std::optional<Affine> fit_affine(const AffineAnchors& anchors, std::span<const vec3> rest,
                                 std::span<const vec3> now, float tolerance = 1e-4f);

}  // namespace bounce
