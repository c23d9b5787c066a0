// What a ray hit: the surface attributes at a Tracer hit, for the G-buffer and the path tracer.
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/render/surface_hit.h"
#include "bounce/render/tangent_frame.h"
#include "bounce/scene/material_eval.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray.h"

namespace bounce {

// What surface_on reads of one triangle: its corners, their normals and texture coordinates
// where the mesh has them, the unit face normal and the material. Loaded once, it serves every
// pixel that sees the triangle (the G-buffer's runs over the raster's candidates).
struct SurfaceTriangle {
  vec3 p0, p1, p2;
  vec3 n0, n1, n2;     // meaningful with has_normals
  vec2 uv0, uv1, uv2;  // meaningful with has_uvs
  vec3 face;
  // Texture coordinates per metre across the triangle (the square root of its areas' ratio in
  // texture space and in space; meaningful with has_uvs): a footprint's width in them.
  float uv_per_metre = 0.0f;
  const MaterialRecord* material = nullptr;
  bool has_normals = false;
  bool has_uvs = false;
};

BOUNCE_HD BOUNCE_LANE_INLINE SurfaceTriangle surface_triangle(const MeshView& mesh,
                                                              const MaterialRecord& material,
                                                              uint32_t triangle) {
  const uvec3 tri = mesh.triangles[triangle];
  SurfaceTriangle t;
  t.p0 = mesh.positions[tri.x];
  t.p1 = mesh.positions[tri.y];
  t.p2 = mesh.positions[tri.z];
  t.face = mesh.unit_face_normal(triangle, tri);
  t.material = &material;
  t.has_normals = mesh.normals != nullptr;
  if (t.has_normals) {
    t.n0 = mesh.normals[tri.x];
    t.n1 = mesh.normals[tri.y];
    t.n2 = mesh.normals[tri.z];
  }
  t.has_uvs = mesh.uvs != nullptr;
  if (t.has_uvs) {
    t.uv0 = mesh.uvs[tri.x];
    t.uv1 = mesh.uvs[tri.y];
    t.uv2 = mesh.uvs[tri.z];
    const vec2 d1 = t.uv1 - t.uv0, d2 = t.uv2 - t.uv0;
    const float uv_area = std::fabs(d1.x * d2.y - d1.y * d2.x);
    const float area = glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
    t.uv_per_metre = area > 0.0f ? std::sqrt(uv_area / area) : 0.0f;
  }
  return t;
}

// Triangle `triangle` of the scene's mesh `mesh`, with its material.
BOUNCE_HD BOUNCE_LANE_INLINE SurfaceTriangle surface_triangle(const SceneView& scene, uint32_t mesh,
                                                              uint32_t triangle) {
  const MeshView& m = scene.meshes[mesh];
  return surface_triangle(m, scene.materials[m.materials[triangle]], triangle);
}

// What a loop over the pixels of one triangle knows of it before it starts (surface_on's kForm):
// where `known`, whether it has normals, texture coordinates and a normal map, and its
// material's form (MaterialForm), so that the loop's lanes have no branch. Unknown (the
// default), the triangle and its material are read.
struct SurfaceForm {
  bool known = false;
  bool normals = false;
  bool uvs = false;
  bool normal_map = false;
  MaterialForm material;

  BOUNCE_HD static constexpr SurfaceForm of(const SurfaceTriangle& t) {
    return {true, t.has_normals, t.has_uvs, t.material->normal_texture >= 0,
            MaterialForm::of(*t.material)};
  }
  BOUNCE_HD constexpr bool has_normals(const SurfaceTriangle& t) const {
    return known ? normals : t.has_normals;
  }
  BOUNCE_HD constexpr bool has_uvs(const SurfaceTriangle& t) const {
    return known ? uvs : t.has_uvs;
  }
  BOUNCE_HD constexpr bool has_normal_map(const MaterialRecord& m) const {
    return known ? normal_map : m.normal_texture >= 0;
  }
  constexpr bool operator==(const SurfaceForm&) const = default;
};

// The surface at barycentric (b1, b2) of triangle t for a ray travelling along `direction`;
// `textures[i].sample(uv)` reads the scene's textures, or with kMeanTextures their means
// (material_at; no normal map then); kForm: what the caller knows of t (SurfaceForm). With
// kFiltered, the ray is a cone `cone_width` wide where it meets the surface (a pixel's footprint)
// and the textures are filtered over that footprint on the surface (TextureView's lookup over
// its levels), the ray cones of Akenine-Moller et al. 2019, "Texture Level of Detail Strategies
// for Real-Time Ray Tracing" (Ray Tracing Gems, ch. 20); else read at the point. The one
// implementation behind every surface_at form.
template <bool kMeanTextures = false, SurfaceForm kForm = SurfaceForm{}, bool kFiltered = false,
          typename Textures>
BOUNCE_HD BOUNCE_LANE_INLINE SurfaceHit surface_on(const SurfaceTriangle& t, vec2 barycentric,
                                                   vec3 direction, const Textures& textures,
                                                   float cone_width = 0.0f) {
  const MaterialRecord& material = *t.material;
  const float b1 = barycentric.x, b2 = barycentric.y, b0 = 1.0f - b1 - b2;

  SurfaceHit s;
  s.position = b0 * t.p0 + b1 * t.p1 + b2 * t.p2;
  const vec3 face = load3(t.face);
  const bool front = glm::dot(face, direction) < 0.0f;
  s.geometric_normal = front ? face : -face;
  // The shading normal as the file has it (interpolated, else the face's), turned to the
  // viewer's side after any normal map: a back face shows the front's perturbation mirrored.
  vec3 normal = face;
  if (kForm.has_normals(t)) {
    const vec3 n = b0 * t.n0 + b1 * t.n1 + b2 * t.n2;
    // One division, not glm's three (vec3 / float): they were a tenth of the G-buffer kernel.
    // Made either way and then picked: no branch, so a loop over a triangle's pixels vectorises
    // (load3 and pick likewise: lane.h).
    const float len = glm::length(n);
    normal = pick(len > 0.0f, n * (1.0f / len), face);
  }
  vec2 uv(0.0f);
  if (kForm.has_uvs(t)) {
    uv = b0 * t.uv0 + b1 * t.uv1 + b2 * t.uv2;
    TangentFrame frame;
    if (!kMeanTextures && kForm.has_normal_map(material) &&
        tangent_frame(t.p0, t.p1, t.p2, t.uv0, t.uv1, t.uv2, normal, frame)) {
      const vec3 mapped = frame.to_world(tangent_space_normal(material, textures, uv));
      const float len = glm::length(mapped);
      if (len > 0.0f) normal = mapped * (1.0f / len);
    }
  }
  // Interpolated normals live on the same side as the face normal we shade from.
  s.normal = glm::dot(normal, s.geometric_normal) < 0.0f ? -normal : normal;
  // A cone meeting the surface at an angle covers an ellipse 1 / cos wider one way: filtered over
  // a square of the same area, which blurs less than the ellipse's long axis would.
  float uv_width = 0.0f;
  if constexpr (kFiltered) {
    const float cos_in = glm::max(std::fabs(glm::dot(direction, face)), 1e-3f);
    uv_width = cone_width * t.uv_per_metre * (1.0f / std::sqrt(cos_in));
  }
  const MaterialPoint m =
      material_at<kMeanTextures, kForm.material, kFiltered>(material, textures, uv, uv_width);
  s.albedo = load3(m.albedo);
  s.f0 = load3(m.f0);
  s.roughness = m.roughness;
  s.emission = pick(front, m.emission, vec3(0.0f));
  return s;
}

// The same at a triangle hit on `mesh`, whose material there is `material`.
template <bool kMeanTextures = false, typename Textures>
BOUNCE_HD SurfaceHit surface_on(const MeshView& mesh, const MaterialRecord& material,
                                const Hit& hit, vec3 direction, const Textures& textures) {
  return surface_on<kMeanTextures>(surface_triangle(mesh, material, hit.triangle), hit.barycentric,
                                   direction, textures);
}

// Evaluates the surface at a triangle `hit` (hit.valid()) for a ray travelling along `direction`
// (kMeanTextures: surface_on's).
template <bool kMeanTextures = false>
BOUNCE_HD inline SurfaceHit surface_at(const SceneView& scene, const Hit& hit, vec3 direction) {
  return surface_on<kMeanTextures>(surface_triangle(scene, hit.mesh, hit.triangle), hit.barycentric,
                                   direction, scene.textures);
}
SurfaceHit surface_at(const Scene& scene, const Hit& hit, vec3 direction);

}  // namespace bounce
