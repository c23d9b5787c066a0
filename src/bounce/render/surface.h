// What a ray hit: the surface attributes at a Tracer hit, for the G-buffer and the path tracer.
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"
#include "bounce/render/surface_hit.h"
#include "bounce/render/tangent_frame.h"
#include "bounce/scene/material_eval.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

// The surface at a triangle hit on `mesh`, whose material there is `material`, for a ray
// travelling along `direction`; `textures[i].sample(uv)` reads the scene's textures, or with
// kMeanTextures their means (material_at; no normal map then). The one implementation behind
// both surface_at forms.
template <bool kMeanTextures = false, typename Textures>
BOUNCE_HD SurfaceHit surface_on(const MeshView& mesh, const MaterialRecord& material,
                                const Hit& hit, vec3 direction, const Textures& textures) {
  const uvec3 tri = mesh.triangles[hit.triangle];
  const float b1 = hit.barycentric.x, b2 = hit.barycentric.y, b0 = 1.0f - b1 - b2;

  SurfaceHit s;
  s.position = b0 * mesh.positions[tri.x] + b1 * mesh.positions[tri.y] + b2 * mesh.positions[tri.z];
  const vec3 face = mesh.unit_face_normal(hit.triangle, tri);
  const bool front = glm::dot(face, direction) < 0.0f;
  s.geometric_normal = front ? face : -face;
  // The shading normal as the file has it (interpolated, else the face's), turned to the
  // viewer's side after any normal map: a back face shows the front's perturbation mirrored.
  vec3 normal = face;
  if (mesh.normals) {
    const vec3 n = b0 * mesh.normals[tri.x] + b1 * mesh.normals[tri.y] + b2 * mesh.normals[tri.z];
    // One division, not glm's three (vec3 / float): they were a tenth of the G-buffer kernel.
    const float len = glm::length(n);
    if (len > 0.0f) normal = n * (1.0f / len);
  }
  vec2 uv(0.0f);
  if (mesh.uvs) {
    uv = b0 * mesh.uvs[tri.x] + b1 * mesh.uvs[tri.y] + b2 * mesh.uvs[tri.z];
    TangentFrame frame;
    if (!kMeanTextures && material.normal_texture >= 0 &&
        tangent_frame(mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z],
                      mesh.uvs[tri.x], mesh.uvs[tri.y], mesh.uvs[tri.z], normal, frame)) {
      const vec3 mapped = frame.to_world(tangent_space_normal(material, textures, uv));
      const float len = glm::length(mapped);
      if (len > 0.0f) normal = mapped * (1.0f / len);
    }
  }
  // Interpolated normals live on the same side as the face normal we shade from.
  s.normal = glm::dot(normal, s.geometric_normal) < 0.0f ? -normal : normal;
  const MaterialPoint m = material_at<kMeanTextures>(material, textures, uv);
  s.albedo = m.albedo;
  s.f0 = m.f0;
  s.roughness = m.roughness;
  s.emission = front ? m.emission : vec3(0.0f);
  return s;
}

// Evaluates the surface at a triangle `hit` (hit.valid()) for a ray travelling along `direction`
// (kMeanTextures: surface_on's).
template <bool kMeanTextures = false>
BOUNCE_HD inline SurfaceHit surface_at(const SceneView& scene, const Hit& hit, vec3 direction) {
  const MeshView& mesh = scene.meshes[hit.mesh];
  return surface_on<kMeanTextures>(mesh, scene.materials[mesh.materials[hit.triangle]], hit,
                                   direction, scene.textures);
}
SurfaceHit surface_at(const Scene& scene, const Hit& hit, vec3 direction);

}  // namespace bounce
