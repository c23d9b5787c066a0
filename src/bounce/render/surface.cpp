#include "bounce/render/surface.h"

namespace bounce {

SurfaceHit surface_at(const Scene& scene, const Hit& hit, vec3 direction) {
  const Mesh& mesh = scene.meshes[hit.mesh];
  const uvec3 tri = mesh.triangles[hit.triangle];
  const float b1 = hit.barycentric.x, b2 = hit.barycentric.y, b0 = 1.0f - b1 - b2;
  const Material& material = scene.materials[mesh.materials[hit.triangle]];

  SurfaceHit s;
  s.material = mesh.materials[hit.triangle];
  s.position = b0 * mesh.positions[tri.x] + b1 * mesh.positions[tri.y] + b2 * mesh.positions[tri.z];
  const vec3 face = glm::normalize(mesh.face_normal_area2(hit.triangle));
  const bool front = glm::dot(face, direction) < 0.0f;
  s.geometric_normal = front ? face : -face;
  s.normal = s.geometric_normal;
  if (!mesh.normals.empty()) {
    const vec3 n = b0 * mesh.normals[tri.x] + b1 * mesh.normals[tri.y] + b2 * mesh.normals[tri.z];
    const float len = glm::length(n);
    // Interpolated normals live on the same side as the face normal we shade from.
    if (len > 0.0f) s.normal = glm::dot(n, s.geometric_normal) < 0.0f ? -n / len : n / len;
  }
  vec2 uv(0.0f);
  if (!mesh.uvs.empty()) uv = b0 * mesh.uvs[tri.x] + b1 * mesh.uvs[tri.y] + b2 * mesh.uvs[tri.z];
  s.albedo = scene.albedo(material, uv);
  s.f0 = material.f0;
  s.roughness = material.roughness;
  s.emission = front ? material.emission : vec3(0.0f);
  return s;
}

}  // namespace bounce
