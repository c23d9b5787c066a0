// A triangle mesh in world space with optional per-vertex normals and UVs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bounce/core/math.h"

namespace bounce {

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
    return glm::cross(positions[i.y] - positions[i.x], positions[i.z] - positions[i.x]);
  }
};

}  // namespace bounce
