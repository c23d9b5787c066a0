#include "bounce/scene/scene.h"

#include <cmath>

#include "bounce/core/error.h"
#include "bounce/scene/scene_limits.h"

namespace bounce {

namespace {

void check_finite(const Scene& s, vec3 v, const std::string& what) {
  if (!is_finite(v)) fail("{}: {} is not finite ({}, {}, {})", s.source, what, v.x, v.y, v.z);
}

void validate_mesh(const Scene& s, const Mesh& m) {
  const std::string where = "mesh '" + m.name + "'";
  const size_t nv = m.positions.size();
  if (!m.normals.empty() && m.normals.size() != nv)
    fail("{}: {} has {} normals for {} vertices", s.source, where, m.normals.size(), nv);
  if (!m.uvs.empty() && m.uvs.size() != nv)
    fail("{}: {} has {} texture coordinates for {} vertices", s.source, where, m.uvs.size(), nv);
  if (m.materials.size() != m.triangles.size())
    fail("{}: {} has {} material ids for {} triangles", s.source, where, m.materials.size(),
         m.triangles.size());
  for (size_t i = 0; i < nv; ++i) {
    if (!is_finite(m.positions[i]))
      fail("{}: {} vertex {} has a non-finite position", s.source, where, i);
    if (!m.normals.empty() && !is_finite(m.normals[i]))
      fail("{}: {} vertex {} has a non-finite normal", s.source, where, i);
    if (!m.uvs.empty() && !(std::isfinite(m.uvs[i].x) && std::isfinite(m.uvs[i].y)))
      fail("{}: {} vertex {} has a non-finite texture coordinate", s.source, where, i);
  }
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const uvec3 tri = m.triangles[t];
    if (tri.x >= nv || tri.y >= nv || tri.z >= nv)
      fail("{}: {} triangle {} has vertex index out of range ({}, {}, {}; {} vertices)", s.source,
           where, t, tri.x, tri.y, tri.z, nv);
    if (m.materials[t] >= s.materials.size())
      fail("{}: {} triangle {} uses material {} of {}", s.source, where, t, m.materials[t],
           s.materials.size());
  }
}

// Finite and at most kMaxEmission; negative values are refused by the callers, each with its
// own message.
void check_emission(const Scene& s, vec3 c, const std::string& what) {
  check_finite(s, c, what);
  if (glm::any(glm::greaterThan(c, vec3(kMaxEmission))))
    fail("{}: {} ({}, {}, {}) is above the limit of {:g}", s.source, what, c.x, c.y, c.z,
         kMaxEmission);
}

void validate_material(const Scene& s, const Material& m) {
  const std::string where = "material '" + m.name + "'";
  check_finite(s, m.albedo, where + " albedo");
  check_finite(s, m.f0, where + " F0");
  check_emission(s, m.emission, where + " emission");
  if (!(m.roughness >= 0.0f && m.roughness <= 1.0f))
    fail("{}: {} roughness {} is outside [0, 1]", s.source, where, m.roughness);
  if (glm::any(glm::lessThan(m.emission, vec3(0.0f))))
    fail("{}: {} has negative emission", s.source, where);
  for (const int t : {m.albedo_texture, m.metal_rough_texture, m.normal_texture, m.emission_texture,
                      m.alpha_texture})
    if (t >= int(s.textures.size()))
      fail("{}: {} uses texture {} of {}", s.source, where, t, s.textures.size());
}

void validate_light(const Scene& s, const Light& l, size_t index) {
  const std::string where = fmt::format("light {} ('{}', {})", index, l.name, l.type_name());
  check_finite(s, l.position, where + " position");
  check_emission(s, l.intensity, where + " intensity");
  check_emission(s, l.irradiance, where + " irradiance");
  check_emission(s, l.radiance, where + " radiance");
  if (!valid_emission(l.emission()))
    fail("{}: {} has a negative {}", s.source, where,
         l.type == LightType::kDirectional ? "irradiance"
         : l.type == LightType::kSphere    ? "radiance"
                                           : "intensity");
  if (l.type == LightType::kSpot || l.type == LightType::kDirectional) {
    if (!is_finite(l.direction) || glm::length(l.direction) < 1e-6f)
      fail("{}: {} has no valid direction", s.source, where);
  }
  if (l.type == LightType::kSphere && !(l.radius > 0.0f && l.radius <= kMaxSceneExtent))
    fail("{}: {} needs a positive radius of at most {:g} m (got {})", s.source, where,
         kMaxSceneExtent, l.radius);
  if (l.type == LightType::kSpot && !(l.cos_outer < l.cos_inner))
    fail("{}: {} needs an outer cone wider than its inner cone", s.source, where);
  if (l.type == LightType::kEnvironment) {
    if (!std::isfinite(l.rotation))
      fail("{}: {} has a rotation that is not finite", s.source, where);
    // What the map multiplies must stay within the emission limit too.
    const float peak =
        max_component(l.radiance) * (s.environment_map ? s.environment_map->max_value() : 1.0f);
    if (!(peak <= kMaxEmission))
      fail("{}: {}: radiance times the map's brightest texel ({:g}) is above the limit of {:g}",
           s.source, where, peak, kMaxEmission);
  }
}

void check_extent(const Scene& s, vec3 p, const std::string& what) {
  if (!within_extent(p))
    fail("{}: {} ({}, {}, {}) is outside the scene extent (|coordinate| <= {:g} m)", s.source, what,
         p.x, p.y, p.z, kMaxSceneExtent);
}

// Frames the scene's bounds from the -z side, like the Cornell box camera.
Camera frame_bounds(const Bounds& b) {
  Camera c;
  c.vfov_deg = 40.0f;
  const vec3 centre = b.centre();
  const float radius = 0.5f * glm::max(b.diagonal(), 1e-3f);
  const float distance = radius / std::tan(glm::radians(c.vfov_deg) * 0.5f);
  c.look_at = centre;
  c.position = centre - vec3(0.0f, 0.0f, distance);
  return c;
}

}  // namespace

void Scene::finalize() {
  if (source.empty()) source = "<scene>";
  for (const auto& m : materials) validate_material(*this, m);
  for (const auto& m : meshes) validate_mesh(*this, m);
  size_t environments = 0;
  for (size_t i = 0; i < lights.size(); ++i) {
    validate_light(*this, lights[i], i);
    if (lights[i].type == LightType::kEnvironment) ++environments;
  }
  if (environments > 1)
    fail("{}: the scene has {} environment lights; at most one is allowed", source, environments);
  if (environment_map && environments == 0)
    fail("{}: the scene has an environment map but no environment light", source);
  for (const auto& t : textures)
    if (t.width <= 0 || t.height <= 0 || t.texels.size() != size_t(t.width) * t.height)
      fail("{}: texture '{}' has inconsistent size", source, t.name);
  if (triangle_count() == 0 && lights.empty()) fail("{}: the scene has no triangles", source);

  for (auto& l : lights) l.direction = glm::normalize(l.direction);
  derive();
  prepare_animation(*this);

  if (!has_camera) {
    // Framed from the bounds, which are within the extent: it may stand a few times the
    // extent away, still far inside what the tracer carries.
    camera = frame_bounds(bounds);
    has_camera = true;
    check_finite(*this, camera.position, "camera position");
  } else {
    check_extent(*this, camera.position, "camera position");
    check_extent(*this, camera.look_at, "camera target");
  }
  if (glm::length(camera.look_at - camera.position) < 1e-9f)
    fail("{}: the camera looks at its own position", source);
  if (!(camera.vfov_deg > 0.0f && camera.vfov_deg < 180.0f))
    fail("{}: camera field of view {} is outside (0, 180) degrees", source, camera.vfov_deg);
}

void Scene::derive() {
  bounds = Bounds{};
  triangle_offsets.clear();
  uint32_t offset = 0;
  for (const auto& m : meshes) {
    triangle_offsets.push_back(offset);
    offset += uint32_t(m.triangle_count());
    // Checked here, where every load, edit and pose passes, so nothing beyond the extent (or
    // not finite) reaches a technique or the tracer.
    for (size_t i = 0; i < m.positions.size(); ++i) {
      if (!within_extent(m.positions[i]))
        check_extent(*this, m.positions[i], fmt::format("mesh '{}' vertex {}", m.name, i));
      bounds.extend(m.positions[i]);
    }
  }
  for (size_t i = 0; i < lights.size(); ++i) {
    Light& l = lights[i];
    if (l.type == LightType::kEnvironment)
      l.map_mean = environment_map ? environment_map->mean() : vec3(1.0f);
    if (l.type == LightType::kDirectional || l.type == LightType::kEnvironment) continue;
    if (!within_extent(l.position))
      check_extent(*this, l.position,
                   fmt::format("light {} ('{}', {}) position", i, l.name, l.type_name()));
    bounds.extend(l.position);
  }

  // Group emissive triangles by (mesh, material) into area lights weighted by area.
  area_lights.clear();
  for (uint32_t mi = 0; mi < meshes.size(); ++mi) {
    const Mesh& m = meshes[mi];
    std::vector<int> light_of_material(materials.size(), -1);
    for (uint32_t t = 0; t < m.triangle_count(); ++t) {
      const Material& mat = materials[m.materials[t]];
      if (!mat.is_emissive()) continue;
      const float area = 0.5f * glm::length(m.face_normal_area2(t));
      if (!(area > 0.0f)) continue;  // degenerate triangles emit nothing
      int& li = light_of_material[m.materials[t]];
      if (li < 0) {
        li = int(area_lights.size());
        // A textured emitter emits its mean texel everywhere (material.h).
        const vec3 radiance =
            mat.emission * (mat.emission_texture >= 0 ? mat.emission_texture_mean : vec3(1.0f));
        area_lights.push_back({m.name + "/" + mat.name, radiance, {}, {}, {}, 0.0f});
      }
      AreaLight& al = area_lights[li];
      al.triangles.push_back({mi, t});
      al.normals.push_back(glm::normalize(m.face_normal_area2(t)));
      al.area += area;
      al.cdf.push_back(al.area);
    }
  }
  for (auto& al : area_lights) {
    for (auto& c : al.cdf) c /= al.area;
    al.cdf.back() = 1.0f;
  }
}

void Scene::append(Scene&& other, const mat4& m) {
  animation.append(std::move(other.animation), uint32_t(meshes.size()), uint32_t(lights.size()), m);
  const uint32_t material_base = uint32_t(materials.size());
  const int texture_base = int(textures.size());
  for (auto& t : other.textures) textures.push_back(std::move(t));
  for (auto& mat : other.materials) {
    for (int* t : {&mat.albedo_texture, &mat.metal_rough_texture, &mat.normal_texture,
                   &mat.emission_texture, &mat.alpha_texture})
      if (*t >= 0) *t += texture_base;
    materials.push_back(std::move(mat));
  }
  for (auto& mesh : other.meshes) {
    for (auto& id : mesh.materials) id += material_base;
    mesh.transform(m);
    meshes.push_back(std::move(mesh));
  }
  if (other.environment_map && !environment_map) environment_map = std::move(other.environment_map);
  const mat3 linear(m);
  for (auto& l : other.lights) {
    l.position = vec3(m * vec4(l.position, 1.0f));
    l.direction = linear * l.direction;
    lights.push_back(std::move(l));
  }
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const auto& m : meshes) n += m.triangle_count();
  return n;
}

vec3 Scene::albedo(const MaterialRecord& material, vec2 uv) const {
  return material_at(material, textures, uv).albedo;
}

void Mesh::transform(const mat4& m) {
  if (m == mat4(1.0f)) return;
  for (auto& p : positions) p = vec3(m * vec4(p, 1.0f));
  const mat3 normal_matrix = glm::transpose(glm::inverse(mat3(m)));
  for (auto& n : normals) n = glm::normalize(normal_matrix * n);
  // A mirroring transform flips the winding's sense; swap two vertices to keep front faces.
  if (glm::determinant(mat3(m)) < 0.0f)
    for (auto& t : triangles) std::swap(t.y, t.z);
}

CameraRays CameraRays::from(const Camera& camera, int width, int height) {
  CameraRays r;
  r.origin = camera.position;
  r.forward = glm::normalize(camera.look_at - camera.position);
  vec3 right = glm::cross(r.forward, camera.up);
  if (glm::length(right) < 1e-6f) right = glm::cross(r.forward, vec3(1.0f, 0.0f, 0.0f));
  right = glm::normalize(right);
  const vec3 up = glm::cross(right, r.forward);
  const float half_h = std::tan(glm::radians(camera.vfov_deg) * 0.5f);
  const float half_w = half_h * float(width) / float(height);
  r.right = right * half_w;
  r.up = up * half_h;
  r.width = float(width);
  r.height = float(height);
  return r;
}

}  // namespace bounce
