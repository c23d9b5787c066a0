// The glTF node tree: meshes (triangle, strip and fan primitives), KHR_lights_punctual lights and
// the first perspective camera, placed by the nodes' TRS or matrix transforms.
//
// Lights: KHR_lights_punctual gives point and spot intensity in candela and directional
// illuminance in lux. bounce renders in radiometric units, and we do NOT convert photometric
// units (that would need a luminous efficacy and a spectrum): colour x intensity is taken as W/sr
// for point and spot lights and as W/m^2 for directional lights.
#include <cmath>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

int attribute(const tg::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

// Triangles from a strip or fan's vertex list, wound as glTF 2.0 (section 3.7.2.1) defines:
// strip triangle i is (v[i], v[i+1+i%2], v[i+2-i%2]), fan triangle i is (v[i+1], v[i+2], v[0]).
std::vector<uint32_t> triangle_list(int mode, const std::vector<uint32_t>& v) {
  std::vector<uint32_t> out;
  if (v.size() < 3) return out;
  out.reserve(3 * (v.size() - 2));
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
      out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    else
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
  }
  return out;
}

void add_primitive(Context& ctx, const tg::Primitive& p, const mat4& world, std::string name,
                   const std::string& where) {
  const bool strip_or_fan =
      p.mode == TINYGLTF_MODE_TRIANGLE_STRIP || p.mode == TINYGLTF_MODE_TRIANGLE_FAN;
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES && !strip_or_fan) {
    if (ctx.skipped_modes.insert(p.mode).second)
      warn(
          fmt::format("{}: skipping primitives of mode {} (points and lines: only triangles, "
                      "strips and fans are rendered)",
                      ctx.path, p.mode));
    return;
  }
  const int position = attribute(p, "POSITION");
  if (position < 0) {
    warn(fmt::format("{}: {} has no POSITION attribute; skipped", ctx.path, where));
    return;
  }
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.positions = read_vec3(ctx, position, where + " POSITION");
  const size_t nv = mesh.positions.size();
  if (const int normal = attribute(p, "NORMAL"); normal >= 0) {
    mesh.normals = read_vec3(ctx, normal, where + " NORMAL");
    if (mesh.normals.size() != nv)
      fail("{}: {}: {} normals for {} positions", ctx.path, where, mesh.normals.size(), nv);
  }
  if (const int uv = attribute(p, "TEXCOORD_0"); uv >= 0) {
    mesh.uvs = read_uv(ctx, uv, where + " TEXCOORD_0");
    if (mesh.uvs.size() != nv)
      fail("{}: {}: {} texture coordinates for {} positions", ctx.path, where, mesh.uvs.size(), nv);
  }
  std::vector<uint32_t> indices;
  if (p.indices >= 0) {
    indices = read_indices(ctx, p.indices, where + " indices");
    for (size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= nv)
        fail("{}: {}: index {} (at {}) is out of range ({} vertices)", ctx.path, where, indices[i],
             i, nv);
  } else {
    indices.resize(nv);
    for (size_t i = 0; i < nv; ++i) indices[i] = uint32_t(i);
  }
  if (strip_or_fan) indices = triangle_list(p.mode, indices);
  if (indices.size() % 3 != 0)
    fail("{}: {}: {} vertex indices do not make whole triangles", ctx.path, where, indices.size());
  if (indices.empty()) return;
  const uint32_t material = scene_material(ctx, p.material, where);
  mesh.triangles.reserve(indices.size() / 3);
  for (size_t i = 0; i < indices.size(); i += 3)
    mesh.triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
  mesh.materials.assign(mesh.triangles.size(), material);

  // Normals that cannot be normalised, or a transform that flattens the mesh, leave no usable
  // shading normals: shade flat instead of producing NaNs.
  const float det = glm::determinant(mat3(world));
  bool usable = std::isfinite(det) && std::abs(det) > 1e-30f;
  for (const vec3& n : mesh.normals) usable &= glm::length(n) > 1e-20f;
  if (!mesh.normals.empty() && !usable) {
    warn(fmt::format("{}: {} has degenerate normals or transform; shading it flat", ctx.path,
                     where));
    mesh.normals.clear();
  }
  for (vec3& n : mesh.normals) n = glm::normalize(n);  // an identity transform keeps them as read
  mesh.transform(world);
  ctx.scene.meshes.push_back(std::move(mesh));
}

}  // namespace

mat4 local_transform(const Context& ctx, const tg::Node& node, int index) {
  const std::string where = fmt::format("node {}", index);
  auto check = [&](const std::vector<double>& v, size_t size, const char* what) {
    if (!v.empty() && v.size() != size)
      fail("{}: {} {} needs {} numbers, found {}", ctx.path, where, what, size, v.size());
    for (double x : v)
      if (!std::isfinite(x)) fail("{}: {} {} is not finite", ctx.path, where, what);
  };
  check(node.matrix, 16, "matrix");
  check(node.translation, 3, "translation");
  check(node.rotation, 4, "rotation");
  check(node.scale, 3, "scale");
  mat4 m(1.0f);
  if (!node.matrix.empty()) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = float(node.matrix[size_t(c * 4 + r)]);  // column-major
    return m;
  }
  if (!node.translation.empty())
    m[3] = vec4(float(node.translation[0]), float(node.translation[1]), float(node.translation[2]),
                1.0f);
  mat3 rs(1.0f);
  if (!node.rotation.empty()) {
    // Unit quaternion (x, y, z, w) -> rotation matrix.
    vec4 q(float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]),
           float(node.rotation[3]));
    const float length = glm::length(q);
    if (!(length > 1e-12f)) fail("{}: {} rotation is not a unit quaternion", ctx.path, where);
    q /= length;
    const float x = q.x, y = q.y, z = q.z, w = q.w;
    rs[0] = vec3(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w));
    rs[1] = vec3(2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w));
    rs[2] = vec3(2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y));
  }
  if (!node.scale.empty())
    for (int c = 0; c < 3; ++c) rs[c] *= float(node.scale[size_t(c)]);
  for (int c = 0; c < 3; ++c) m[c] = vec4(rs[c], 0.0f);
  return m;
}

namespace {

// The unit direction of a node's local -Z axis in the world, or false when it collapses.
bool world_axis(const mat4& world, vec3 local, vec3* out) {
  const vec3 d = mat3(world) * local;
  const float length = glm::length(d);
  if (!(length > 1e-20f) || !std::isfinite(length)) return false;
  *out = d / length;
  return true;
}

void add_light(Context& ctx, const tg::Node& node, int node_index, const mat4& world) {
  const tg::Value* ext = extension(node.extensions, "KHR_lights_punctual");
  if (ext == nullptr || !ext->Has("light")) return;
  const tg::Value& ref = ext->Get("light");
  const std::string where = fmt::format("node {} light", node_index);
  if (!ref.IsNumber()) fail("{}: {} is not a light index", ctx.path, where);
  const double index = ref.GetNumberAsDouble();
  if (!(index >= 0 && index < double(ctx.model.lights.size())) || index != std::floor(index))
    fail("{}: {} {} does not exist ({} lights)", ctx.path, where, index, ctx.model.lights.size());
  const tg::Light& l = ctx.model.lights[size_t(index)];
  const vec3 colour = l.color.empty() ? vec3(1.0f) : vec3_from(ctx, l.color, 3, where + " color");
  const float intensity = finite_number(ctx, l.intensity, where + " intensity");
  if (intensity < 0.0f || glm::any(glm::lessThan(colour, vec3(0.0f))))
    fail("{}: {} has negative intensity or colour", ctx.path, where);
  const vec3 value = colour * intensity;  // radiometric, see the top of the file
  const vec3 position = vec3(world * vec4(0.0f, 0.0f, 0.0f, 1.0f));
  vec3 direction(0.0f, 0.0f, -1.0f);
  const bool has_direction = world_axis(world, vec3(0.0f, 0.0f, -1.0f), &direction);
  Light light;
  if (l.type == "point") {
    light = Light::point(position, value);
  } else if (l.type == "spot" || l.type == "directional") {
    if (!has_direction) {
      warn(fmt::format("{}: {}: the node's transform has no -Z direction; light skipped", ctx.path,
                       where));
      return;
    }
    if (l.type == "directional") {
      light = Light::directional(direction, value);
    } else {
      const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
      if (!(inner >= 0.0 && inner < outer && outer <= 0.5 * kPi + 1e-6))
        fail("{}: {} cone angles must satisfy 0 <= inner < outer <= pi/2 (inner {}, outer {})",
             ctx.path, where, inner, outer);
      light = Light::spot(position, direction, value, glm::degrees(float(inner)),
                          glm::degrees(float(outer)));
    }
  } else {
    warn(fmt::format("{}: {}: unknown light type '{}'; skipped", ctx.path, where, l.type));
    return;
  }
  light.name = !l.name.empty() ? l.name : node.name;
  ctx.scene.lights.push_back(light);
}

void set_camera(Context& ctx, const tg::Node& node, int node_index, const mat4& world) {
  if (node.camera < 0 || ctx.camera_found) return;
  if (size_t(node.camera) >= ctx.model.cameras.size())
    fail("{}: node {} uses camera {}, which does not exist ({} cameras)", ctx.path, node_index,
         node.camera, ctx.model.cameras.size());
  const tg::Camera& c = ctx.model.cameras[size_t(node.camera)];
  if (c.type != "perspective") return;
  const double yfov = c.perspective.yfov;
  if (!(yfov > 0.0 && yfov < kPi))
    fail("{}: camera {} has a vertical field of view of {} radians", ctx.path, node.camera, yfov);
  vec3 forward, up;
  if (!world_axis(world, vec3(0.0f, 0.0f, -1.0f), &forward) ||
      !world_axis(world, vec3(0.0f, 1.0f, 0.0f), &up)) {
    warn(fmt::format("{}: node {}: camera transform is degenerate; camera skipped", ctx.path,
                     node_index));
    return;
  }
  Camera& camera = ctx.scene.camera;
  camera.position = vec3(world * vec4(0.0f, 0.0f, 0.0f, 1.0f));
  camera.look_at = camera.position + forward;
  camera.up = up;
  camera.vfov_deg = glm::degrees(float(yfov));
  ctx.scene.has_camera = true;
  ctx.camera_found = true;
}

void add_node_mesh(Context& ctx, const tg::Node& node, int node_index, const mat4& world) {
  if (node.mesh < 0) return;
  if (size_t(node.mesh) >= ctx.model.meshes.size())
    fail("{}: node {} uses mesh {}, which does not exist ({} meshes)", ctx.path, node_index,
         node.mesh, ctx.model.meshes.size());
  const tg::Mesh& mesh = ctx.model.meshes[size_t(node.mesh)];
  std::string name = !mesh.name.empty()   ? mesh.name
                     : !node.name.empty() ? node.name
                                          : fmt::format("mesh{}", node.mesh);
  for (size_t i = 0; i < mesh.primitives.size(); ++i) {
    const std::string where = fmt::format("mesh {} ('{}') primitive {}", node.mesh, name, i);
    add_primitive(ctx, mesh.primitives[i], world,
                  mesh.primitives.size() == 1 ? name : fmt::format("{}#{}", name, i), where);
  }
}

// The root nodes of the default scene (or of the first, or every parentless node if none).
std::vector<int> root_nodes(const Context& ctx) {
  const tg::Model& m = ctx.model;
  if (m.defaultScene >= 0) {
    if (size_t(m.defaultScene) >= m.scenes.size())
      fail("{}: the default scene {} does not exist ({} scenes)", ctx.path, m.defaultScene,
           m.scenes.size());
    return m.scenes[size_t(m.defaultScene)].nodes;
  }
  if (!m.scenes.empty()) return m.scenes[0].nodes;
  std::vector<char> is_child(m.nodes.size(), 0);
  for (const auto& n : m.nodes)
    for (int c : n.children)
      if (c >= 0 && size_t(c) < m.nodes.size()) is_child[size_t(c)] = 1;
  std::vector<int> roots;
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (!is_child[i]) roots.push_back(int(i));
  return roots;
}

}  // namespace

// Depth-first, parents before children and in file order (so "the first camera" is well
// defined), without recursion so that deep hierarchies cannot overflow the stack.
void walk_nodes(Context& ctx) {
  const tg::Model& m = ctx.model;
  const size_t n = m.nodes.size();
  ctx.visited.assign(n, 0);
  ctx.parent_of.assign(n, -1);
  ctx.world_of.assign(n, mat4(1.0f));
  ctx.meshes_of.assign(n, {0u, 0u});
  ctx.lights_of.assign(n, {0u, 0u});
  struct Entry {
    int index;
    int parent;
    mat4 parent_world;
  };
  std::vector<Entry> stack;
  const std::vector<int> roots = root_nodes(ctx);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, mat4(1.0f)});
  while (!stack.empty()) {
    const Entry e = stack.back();
    const int index = e.index;
    stack.pop_back();
    if (index < 0 || size_t(index) >= n)
      fail("{}: node {} does not exist ({} nodes)", ctx.path, index, n);
    if (ctx.visited[size_t(index)])
      fail("{}: node {} is reached twice (the node hierarchy has a cycle or a shared child)",
           ctx.path, index);
    ctx.visited[size_t(index)] = 1;
    ctx.walk_order.push_back(index);
    ctx.parent_of[size_t(index)] = e.parent;
    const tg::Node& node = m.nodes[size_t(index)];
    const mat4 world = e.parent_world * local_transform(ctx, node, index);
    ctx.world_of[size_t(index)] = world;
    const uint32_t first_mesh = uint32_t(ctx.scene.meshes.size());
    add_node_mesh(ctx, node, index, world);
    ctx.meshes_of[size_t(index)] = {first_mesh, uint32_t(ctx.scene.meshes.size())};
    const uint32_t first_light = uint32_t(ctx.scene.lights.size());
    add_light(ctx, node, index, world);
    ctx.lights_of[size_t(index)] = {first_light, uint32_t(ctx.scene.lights.size())};
    set_camera(ctx, node, index, world);
    if (node.skin >= 0) ctx.ignored.insert("skins");
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
      stack.push_back({*it, index, world});
  }
}

}  // namespace bounce::gltf
