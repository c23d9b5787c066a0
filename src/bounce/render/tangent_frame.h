// Tangent frames for normal maps, computed per hit from the triangle's texture coordinates: the
// per-triangle derivatives dP/du and dP/dv (Lengyel, "Computing Tangent Space Basis Vectors for
// an Arbitrary Mesh", 2001), the tangent made orthogonal to the interpolated shading normal
// (Gram-Schmidt). glTF's convention: the tangent runs along +u and the bitangent is
// cross(n, t) * w, which points up the image (towards -v: glTF's v runs down); w = -1 where the
// uvs are mirrored. Files' TANGENT attributes are not read: these frames follow the mesh as it
// animates and need no per-vertex storage (or device copy).
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct TangentFrame {
  vec3 tangent{1.0f, 0.0f, 0.0f};
  vec3 bitangent{0.0f, 1.0f, 0.0f};
  vec3 normal{0.0f, 0.0f, 1.0f};

  BOUNCE_HD vec3 to_world(vec3 v) const { return tangent * v.x + bitangent * v.y + normal * v.z; }
};

// The frame at unit shading normal `n` on the triangle (p0, p1, p2) with uvs (uv0, uv1, uv2);
// false (frame untouched) where the uvs are degenerate or run along n.
BOUNCE_HD inline bool tangent_frame(vec3 p0, vec3 p1, vec3 p2, vec2 uv0, vec2 uv1, vec2 uv2, vec3 n,
                                    TangentFrame& frame) {
  const vec3 e1 = p1 - p0, e2 = p2 - p0;
  const vec2 d1 = uv1 - uv0, d2 = uv2 - uv0;
  const float det = d1.x * d2.y - d2.x * d1.y;
  if (!(std::fabs(det) > 1e-20f)) return false;
  // dP/du and dP/dv, both scaled by det (only their directions are used).
  const vec3 dpdu = e1 * d2.y - e2 * d1.y;
  const vec3 dpdv = e2 * d1.x - e1 * d2.x;
  const float sign = det < 0.0f ? -1.0f : 1.0f;
  const vec3 t = (dpdu - n * glm::dot(n, dpdu)) * sign;
  const float len = glm::length(t);
  if (!(len > 1e-20f * glm::length(dpdu))) return false;
  frame.normal = n;
  frame.tangent = t / len;
  const vec3 b = glm::cross(n, frame.tangent);
  frame.bitangent = glm::dot(b, dpdv) * sign > 0.0f ? -b : b;
  return true;
}

}  // namespace bounce
