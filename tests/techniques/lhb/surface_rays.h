// Rays the gather sends: from a random point of a mesh's triangle, along a buffer direction at
// least 0.2 (in cosine) above the triangle's front face, from the offset origin a path vertex uses.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene.h"

namespace bounce::lhb_test {

struct SurfaceRay {
  uint32_t prim = 0;  // the triangle it leaves (global id)
  int direction = 0;  // index into the buffer directions
  vec3 origin{0.0f};
};

// A random triangle of mesh m, a random direction and a random point of the triangle; nullopt
// when the triangle is degenerate or the direction is not above it (the caller draws again).
inline std::optional<SurfaceRay> draw_surface_ray(const Scene& s, uint32_t m,
                                                  const std::vector<vec3>& dirs, Pcg32& rng) {
  const Mesh& mesh = s.meshes[m];
  const uint32_t t = rng.next_below(uint32_t(mesh.triangles.size()));
  const vec3 n_area = mesh.face_normal_area2(t);
  if (glm::length(n_area) == 0.0f) return std::nullopt;
  const vec3 n = glm::normalize(n_area);
  const int d = int(rng.next_below(uint32_t(dirs.size())));
  if (glm::dot(n, dirs[size_t(d)]) < 0.2f) return std::nullopt;
  vec2 b = rng.next2();
  if (b.x + b.y > 1.0f) b = vec2(1.0f) - b;
  const uvec3 i = mesh.triangles[t];
  const vec3 p = mesh.positions[i.x] + b.x * (mesh.positions[i.y] - mesh.positions[i.x]) +
                 b.y * (mesh.positions[i.z] - mesh.positions[i.x]);
  return SurfaceRay{s.triangle_offsets[m] + t, d, offset_origin(p, n)};
}

}  // namespace bounce::lhb_test
