// Geometry built by hand in tests: quads, inward-facing boxes and a bumpy ball.
#pragma once

#include <cmath>
#include <string>

#include "bounce/scene/mesh.h"
#include "bounce/scene/scene.h"

namespace bounce::scene_test {

// Appends the parallelogram corner, corner + u, corner + u + v, corner + v as triangles
// (0,1,2), (0,2,3); it faces where cross(u, v) points.
inline void add_quad(Mesh& mesh, vec3 corner, vec3 u, vec3 v, uint32_t material) {
  const uint32_t base = uint32_t(mesh.positions.size());
  for (const vec3& p : {corner, corner + u, corner + u + v, corner + v})
    mesh.positions.push_back(p);
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  mesh.materials.insert(mesh.materials.end(), 2, material);
}

// A mesh of one quad (add_quad).
inline Mesh quad_mesh(const std::string& name, vec3 corner, vec3 u, vec3 v, uint32_t material) {
  Mesh mesh;
  mesh.name = name;
  add_quad(mesh, corner, u, v, material);
  return mesh;
}

// The six faces of the box between corners lo and hi, facing inwards: a room seen from inside.
inline Mesh inward_box(const std::string& name, vec3 lo, vec3 hi, uint32_t material) {
  Mesh mesh;
  mesh.name = name;
  const vec3 size = hi - lo;
  for (int axis = 0; axis < 3; ++axis) {
    // cross(e1, e2) is the axis itself, so (u, v) faces the lo wall inwards; the hi wall swaps.
    vec3 e1(0.0f), e2(0.0f);
    e1[(axis + 1) % 3] = size[(axis + 1) % 3];
    e2[(axis + 2) % 3] = size[(axis + 2) % 3];
    add_quad(mesh, lo, e1, e2, material);
    vec3 far_corner = lo;
    far_corner[axis] = hi[axis];
    add_quad(mesh, far_corner, e2, e1, material);
  }
  return mesh;
}

// Appends a grey material with alpha cut-outs: an alpha texture of four texels (1, 1, 0, 0)
// along u, so its right half is a hole (cutoff 0.5). Returns the material's index.
inline uint32_t add_half_cut_out_material(Scene& s) {
  Material leaf;
  leaf.albedo = vec3(0.5f);
  leaf.alpha_mode = AlphaMode::kMask;
  leaf.alpha_cutoff = 0.5f;
  leaf.alpha_texture = int(s.textures.size());
  s.materials.push_back(leaf);
  Texture alpha;
  alpha.width = 4;
  alpha.height = 1;
  alpha.texels = {vec3(1.0f), vec3(1.0f), vec3(0.0f), vec3(0.0f)};
  s.textures.push_back(alpha);
  return uint32_t(s.materials.size() - 1);
}

// A scene of the unit quad at z = 0 facing +z, its texture coordinates its x and y, with one
// material of albedo `albedo` times `texture`.
inline Scene textured_unit_quad(const Texture& texture, vec3 albedo) {
  Scene s;
  s.textures.push_back(texture);
  Material m;
  m.name = texture.name;
  m.albedo = albedo;
  m.albedo_texture = 0;
  s.materials.push_back(m);
  Mesh quad = quad_mesh("quad", vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), 0);
  quad.uvs = {vec2(0.0f), vec2(1.0f, 0.0f), vec2(1.0f), vec2(0.0f, 1.0f)};
  s.meshes.push_back(quad);
  s.finalize();
  return s;
}

// An outward sphere of 2 r^2 triangles with bumps, so that no rotation maps it onto itself.
inline Mesh bumpy_ball(int r, vec3 centre, float radius, uint32_t material = 0) {
  Mesh m;
  m.name = "ball";
  for (int i = 0; i <= r; ++i)
    for (int j = 0; j <= r; ++j) {
      const float theta = kPi * float(i) / float(r), phi = 2.0f * kPi * float(j) / float(r);
      const float bump = 1.0f + 0.2f * std::sin(3.0f * theta) * std::sin(2.0f * phi);
      m.positions.push_back(centre + radius * bump *
                                         vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                              std::sin(theta) * std::sin(phi)));
    }
  const auto at = [&](int i, int j) { return uint32_t(i * (r + 1) + j); };
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < r; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
    }
  m.materials.assign(m.triangles.size(), material);
  return m;
}

}  // namespace bounce::scene_test
