// A triangle mesh in world space with optional per-vertex normals and UVs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// Unnormalised geometric normal of a triangle by its winding: cross(p1 - p0, p2 - p0).
BOUNCE_HD inline vec3 triangle_normal_area2(vec3 p0, vec3 p1, vec3 p2) {
  return glm::cross(p1 - p0, p2 - p0);
}

// The unit normal of triangle (p0, p1, p2) by its winding, from edges (and then their cross
// product) scaled to unit size first:
// a triangle a few float steps wide (edges of 1e-38 m, which a malformed file can hold) has a
// cross product that underflows to 0, and normalising that gives NaN, which then reaches rays.
// A degenerate triangle (no ray can hit it) gets +z.
BOUNCE_HD inline vec3 triangle_unit_normal(vec3 p0, vec3 p1, vec3 p2) {
  vec3 e1 = p1 - p0, e2 = p2 - p0;
  const vec3 a1 = glm::abs(e1), a2 = glm::abs(e2);
  const float largest =
      glm::max(glm::max(glm::max(a1.x, a1.y), glm::max(a1.z, a2.x)), glm::max(a2.y, a2.z));
  if (!(largest > 0.0f) || !(largest <= 3.0e38f)) return vec3(0.0f, 0.0f, 1.0f);
  // The usual triangle: one reciprocal and one square root. Every G-buffer pixel and photon hit
  // calls this, and a chain of a dozen divisions was a tenth of the G-buffer's time.
  if (largest >= 1.0e-30f) {
    const float inv = 1.0f / largest;
    const vec3 n = glm::cross(e1 * inv, e2 * inv);
    const float len2 = glm::dot(n, n);
    if (len2 >= 1.0e-30f) return n * (1.0f / std::sqrt(len2));
  }
  e1 /= largest;
  e2 /= largest;
  vec3 n = glm::cross(e1, e2);  // a sliver's can still be tiny: scaled again before its length
  const vec3 a = glm::abs(n);
  const float m = glm::max(glm::max(a.x, a.y), a.z);
  if (!(m > 0.0f)) return vec3(0.0f, 0.0f, 1.0f);
  n /= m;
  return n / glm::length(n);
}

// A mesh's arrays as plain pointers for kernels (SceneView holds one per mesh).
struct MeshView {
  const vec3* positions = nullptr;
  const vec3* normals = nullptr;  // per vertex, or null for flat shading
  const vec2* uvs = nullptr;      // per vertex, or null
  const uvec3* triangles = nullptr;
  const uint32_t* materials = nullptr;  // per triangle, index into the scene's materials
  uint32_t vertex_count = 0;
  uint32_t triangle_count = 0;
  // Where the vertices were before the last refresh moved them (the previous frame's pose), or
  // null when the mesh did not move: what motion vectors of moving objects are made from.
  const vec3* previous_positions = nullptr;
  // Per triangle, triangle_unit_normal of its corners made once (SceneData), or null: then each
  // lookup computes it. A division and a square root in a dependent chain were a fifth of the
  // G-buffer kernel's samples (docs/benchmarks.md).
  const vec3* face_normals = nullptr;

  // Triangle t's unit normal by its winding; `tri` is triangles[t].
  BOUNCE_HD vec3 unit_face_normal(uint32_t t, uvec3 tri) const {
    return face_normals
               ? face_normals[t]
               : triangle_unit_normal(positions[tri.x], positions[tri.y], positions[tri.z]);
  }

  BOUNCE_HD vec3 face_normal_area2(uint32_t t) const {
    const uvec3 i = triangles[t];
    return triangle_normal_area2(positions[i.x], positions[i.y], positions[i.z]);
  }
};

struct Mesh {
  std::string name;
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // per vertex, or empty for flat shading
  std::vector<vec2> uvs;      // per vertex, or empty
  std::vector<uvec3> triangles;
  std::vector<uint32_t> materials;  // per triangle, index into Scene::materials

  size_t triangle_count() const { return triangles.size(); }
  // Applies an affine transform to positions and (by the inverse transpose) normals.
  void transform(const mat4& m);
  // Unnormalised geometric normal of triangle t by its winding: cross(p1 - p0, p2 - p0).
  vec3 face_normal_area2(uint32_t t) const {
    const uvec3 i = triangles[t];
    return triangle_normal_area2(positions[i.x], positions[i.y], positions[i.z]);
  }
  // Points into this mesh's arrays: valid until they are resized.
  MeshView view() const {
    return {positions.data(),
            normals.empty() ? nullptr : normals.data(),
            uvs.empty() ? nullptr : uvs.data(),
            triangles.data(),
            materials.data(),
            uint32_t(positions.size()),
            uint32_t(triangles.size())};
  }
};

}  // namespace bounce
