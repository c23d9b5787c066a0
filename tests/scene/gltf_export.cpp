#include "gltf_export.h"

#include <cstring>
#include <map>
#include <vector>

#include <tiny_gltf.h>

#include "bounce/core/error.h"

namespace bounce {

namespace {

namespace tg = tinygltf;

// Appends raw bytes to buffer 0 as a new bufferView (4-byte aligned) and returns its index.
int add_view(tg::Model& model, const void* data, size_t size, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  while (buffer.size() % 4 != 0) buffer.push_back(0);
  tg::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = size;
  view.target = target;
  const auto* bytes = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), bytes, bytes + size);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

template <typename T>
int add_accessor(tg::Model& model, const std::vector<T>& values, int component_type, int type,
                 int target) {
  tg::Accessor a;
  a.bufferView = add_view(model, values.data(), values.size() * sizeof(T), target);
  a.componentType = component_type;
  a.type = type;
  a.count = values.size();
  model.accessors.push_back(a);
  return int(model.accessors.size() - 1);
}

tg::Value object(std::initializer_list<std::pair<const std::string, tg::Value>> members) {
  return tg::Value(tg::Value::Object(members));
}

tg::Material export_material(const Material& m) {
  tg::Material out;
  out.name = m.name;
  out.pbrMetallicRoughness.baseColorFactor = {m.albedo.x, m.albedo.y, m.albedo.z, 1.0};
  out.pbrMetallicRoughness.metallicFactor = 0.0;
  out.pbrMetallicRoughness.roughnessFactor = m.roughness;
  if (max_component(m.f0) > 0.0f) {
    const vec3 c = m.f0 / 0.04f;
    out.extensions["KHR_materials_specular"] =
        object({{"specularFactor", tg::Value(1.0)},
                {"specularColorFactor",
                 tg::Value(tg::Value::Array{tg::Value(double(c.x)), tg::Value(double(c.y)),
                                            tg::Value(double(c.z))})}});
  } else {
    out.extensions["KHR_materials_specular"] = object({{"specularFactor", tg::Value(0.0)}});
  }
  const float strength = max_component(m.emission);
  if (strength > 1.0f) {
    const vec3 e = m.emission / strength;
    out.emissiveFactor = {e.x, e.y, e.z};
    out.extensions["KHR_materials_emissive_strength"] =
        object({{"emissiveStrength", tg::Value(double(strength))}});
  } else {
    out.emissiveFactor = {m.emission.x, m.emission.y, m.emission.z};
  }
  return out;
}

// A node matrix whose local -Z points along `forward` and whose +Y is `up` made orthogonal.
std::vector<double> oriented_matrix(vec3 position, vec3 forward, vec3 up) {
  const vec3 z = -glm::normalize(forward);
  if (glm::length(glm::cross(up, z)) < 1e-6f)
    up = std::abs(z.y) < 0.9f ? vec3(0, 1, 0) : vec3(1, 0, 0);
  const vec3 x = glm::normalize(glm::cross(up, z));
  const vec3 y = glm::cross(z, x);
  return {x.x, x.y, x.z, 0, y.x,        y.y,        y.z,        0,
          z.x, z.y, z.z, 0, position.x, position.y, position.z, 1};
}

void export_mesh(tg::Model& model, const Mesh& mesh) {
  tg::Mesh out;
  out.name = mesh.name;
  tg::Accessor* position_accessor = nullptr;
  const int positions = add_accessor(model, mesh.positions, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                     TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
  position_accessor = &model.accessors[size_t(positions)];
  vec3 lo(INFINITY), hi(-INFINITY);
  for (const vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  position_accessor->minValues = {lo.x, lo.y, lo.z};
  position_accessor->maxValues = {hi.x, hi.y, hi.z};
  const int normals = mesh.normals.empty()
                          ? -1
                          : add_accessor(model, mesh.normals, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                         TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
  const int uvs = mesh.uvs.empty() ? -1
                                   : add_accessor(model, mesh.uvs, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                  TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
  // One primitive per material, in order of first use.
  std::map<uint32_t, std::vector<uint32_t>> by_material;
  std::vector<uint32_t> order;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    auto [it, inserted] = by_material.try_emplace(mesh.materials[t]);
    if (inserted) order.push_back(mesh.materials[t]);
    const uvec3 tri = mesh.triangles[t];
    it->second.insert(it->second.end(), {tri.x, tri.y, tri.z});
  }
  for (uint32_t material : order) {
    tg::Primitive p;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.material = int(material);
    p.attributes["POSITION"] = positions;
    if (normals >= 0) p.attributes["NORMAL"] = normals;
    if (uvs >= 0) p.attributes["TEXCOORD_0"] = uvs;
    p.indices = add_accessor(model, by_material[material], TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                             TINYGLTF_TYPE_SCALAR, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    out.primitives.push_back(p);
  }
  model.meshes.push_back(out);
  tg::Node node;
  node.name = mesh.name;
  node.mesh = int(model.meshes.size() - 1);
  model.nodes.push_back(node);
}

void export_light(tg::Model& model, const Light& l) {
  tg::Light out;
  out.name = l.name;
  vec3 value = l.intensity;
  switch (l.type) {
    case LightType::kPoint:
      out.type = "point";
      break;
    case LightType::kSphere:
      out.type = "point";
      value = l.radiance * (kPi * l.radius * l.radius);
      break;
    case LightType::kSpot:
      out.type = "spot";
      out.spot.innerConeAngle = std::acos(glm::clamp(l.cos_inner, -1.0f, 1.0f));
      out.spot.outerConeAngle = std::acos(glm::clamp(l.cos_outer, -1.0f, 1.0f));
      break;
    case LightType::kDirectional:
      out.type = "directional";
      value = l.irradiance;
      break;
    case LightType::kEnvironment:
      return;  // glTF has no environment light
  }
  const float intensity = max_component(value);
  const vec3 colour = intensity > 0.0f ? value / intensity : vec3(1.0f);
  out.color = {colour.x, colour.y, colour.z};
  out.intensity = intensity;
  model.lights.push_back(out);

  tg::Node node;
  node.name = l.name;
  node.matrix = oriented_matrix(l.position, l.direction, vec3(0, 1, 0));
  node.extensions["KHR_lights_punctual"] =
      object({{"light", tg::Value(int(model.lights.size() - 1))}});
  model.nodes.push_back(node);
}

void export_camera(tg::Model& model, const Camera& c) {
  tg::Camera out;
  out.type = "perspective";
  out.perspective.yfov = glm::radians(double(c.vfov_deg));
  out.perspective.znear = 1e-3;
  model.cameras.push_back(out);
  tg::Node node;
  node.name = "camera";
  node.camera = int(model.cameras.size() - 1);
  node.matrix = oriented_matrix(c.position, c.look_at - c.position, c.up);
  model.nodes.push_back(node);
}

}  // namespace

void write_scene_as_gltf(const Scene& scene, const std::string& path, bool binary) {
  tg::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "bounce tests";
  model.buffers.resize(1);
  for (const Material& m : scene.materials) model.materials.push_back(export_material(m));
  for (const Mesh& mesh : scene.meshes) export_mesh(model, mesh);
  for (const Light& l : scene.lights) export_light(model, l);
  if (scene.has_camera) export_camera(model, scene.camera);
  model.extensionsUsed = {"KHR_materials_emissive_strength", "KHR_materials_specular"};
  tg::Scene root;
  for (size_t i = 0; i < model.nodes.size(); ++i) root.nodes.push_back(int(i));
  model.scenes.push_back(root);
  model.defaultScene = 0;
  tg::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path, /*embedImages=*/true, /*embedBuffers=*/true,
                                   /*prettyPrint=*/true, binary))
    fail("{}: cannot write glTF", path);
}

}  // namespace bounce
