// What a ray hit: the surface attributes at a Tracer hit, for the G-buffer and the path tracer.
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/surface_hit.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

// The surface at a triangle hit on `mesh`, whose material there is `material`, for a ray
// travelling along `direction`; albedo(material, uv) gives the (textured) diffuse albedo. The one
// implementation behind both surface_at forms.
template <typename Albedo>
BOUNCE_HD SurfaceHit surface_on(const MeshView& mesh, const MaterialRecord& material,
                                const Hit& hit, vec3 direction, const Albedo& albedo) {
  const uvec3 tri = mesh.triangles[hit.triangle];
  const float b1 = hit.barycentric.x, b2 = hit.barycentric.y, b0 = 1.0f - b1 - b2;

  SurfaceHit s;
  s.position = b0 * mesh.positions[tri.x] + b1 * mesh.positions[tri.y] + b2 * mesh.positions[tri.z];
  const vec3 face = glm::normalize(mesh.face_normal_area2(hit.triangle));
  const bool front = glm::dot(face, direction) < 0.0f;
  s.geometric_normal = front ? face : -face;
  s.normal = s.geometric_normal;
  if (mesh.normals) {
    const vec3 n = b0 * mesh.normals[tri.x] + b1 * mesh.normals[tri.y] + b2 * mesh.normals[tri.z];
    const float len = glm::length(n);
    // Interpolated normals live on the same side as the face normal we shade from.
    if (len > 0.0f) s.normal = glm::dot(n, s.geometric_normal) < 0.0f ? -n / len : n / len;
  }
  vec2 uv(0.0f);
  if (mesh.uvs) uv = b0 * mesh.uvs[tri.x] + b1 * mesh.uvs[tri.y] + b2 * mesh.uvs[tri.z];
  s.albedo = albedo(material, uv);
  s.f0 = material.f0;
  s.roughness = material.roughness;
  s.emission = front ? material.emission : vec3(0.0f);
  return s;
}

// Evaluates the surface at a triangle `hit` (hit.valid()) for a ray travelling along `direction`.
BOUNCE_HD inline SurfaceHit surface_at(const SceneView& scene, const Hit& hit, vec3 direction) {
  const MeshView& mesh = scene.meshes[hit.mesh];
  return surface_on(mesh, scene.materials[mesh.materials[hit.triangle]], hit, direction,
                    [&](const MaterialRecord& m, vec2 uv) { return scene.albedo(m, uv); });
}
SurfaceHit surface_at(const Scene& scene, const Hit& hit, vec3 direction);

}  // namespace bounce
