// glTF 2.0 (.gltf and .glb) through tinygltf.
//
// What is read: the default scene's node tree (TRS or matrix transforms), TRIANGLES primitives
// (indexed or not) with POSITION, NORMAL and TEXCOORD_0; metallic-roughness materials with
// KHR_materials_emissive_strength and KHR_materials_specular; KHR_lights_punctual; the first
// perspective camera; node animations (translation, rotation and scale channels of every
// animation in the file, played together) as TrsTracks. tinygltf parses the JSON and the GLB
// container; every index, count and byte range it hands over is checked here before use, since a
// broken file must give an error, never an out-of-bounds read.
//
// Lights: KHR_lights_punctual gives point and spot intensity in candela and directional
// illuminance in lux. bounce renders in radiometric units, and we do NOT convert photometric
// units (that would need a luminous efficacy and a spectrum): colour x intensity is taken as W/sr
// for point and spot lights and as W/m^2 for directional lights.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <tiny_gltf.h>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/scene/load.h"

namespace bounce {

namespace {

namespace tg = tinygltf;

// The extensions whose meaning we implement; a file that requires any other is refused.
const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular"};

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// ---------------------------------------------------------------------------------------------
// Loading the file

// tinygltf's image callback. Images stored in a bufferView are left for later: tinygltf passes a
// pointer into the buffer without checking the view's range, so they are decoded only after
// decode_buffer_view_image has checked it. An image that cannot be decoded is not an error: the
// material falls back to its base colour factor.
bool decode_image(tg::Image* image, const int index, std::string* err, std::string* warnings,
                  int width, int height, const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;
  std::string error;
  if (bytes == nullptr || size <= 0 ||
      !tg::LoadImageData(image, index, &error, warnings, width, height, bytes, size, nullptr)) {
    if (warnings) *warnings += "image " + std::to_string(index) + " cannot be decoded\n";
    image->image.clear();
  }
  return true;
}

bool is_glb(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && std::memcmp(magic, "glTF", 4) == 0;
}

void forward_warnings(const std::string& warnings, const std::string& path) {
  std::istringstream lines(warnings);
  std::string line;
  while (std::getline(lines, line))
    if (!trim(line).empty()) warn(path + ": " + trim(line));
}

tg::Model read_model(const std::string& path) {
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail("{}: cannot open the file", path);
  }
  tg::TinyGLTF loader;
  loader.SetImageLoader(&decode_image, nullptr);
  tg::Model model;
  std::string error, warnings;
  const bool ok = is_glb(path) ? loader.LoadBinaryFromFile(&model, &error, &warnings, path)
                               : loader.LoadASCIIFromFile(&model, &error, &warnings, path);
  if (!ok) {
    error = trim(error);
    if (error.empty()) error = trim(warnings);
    // nlohmann's "[json.exception.parse_error.101] " prefix says nothing to a user.
    if (const size_t end = error.find("] ");
        error.starts_with("[json.") && end != std::string::npos)
      error = error.substr(end + 2);
    fail("{}: cannot load glTF: {}", path, error.empty() ? "unknown error" : error);
  }
  forward_warnings(warnings, path);
  std::vector<std::string> unsupported;
  for (const auto& e : model.extensionsRequired)
    if (!kSupportedExtensions.count(e)) unsupported.push_back(e);
  if (!unsupported.empty())
    fail("{}: requires glTF extension(s) {} which bounce does not support", path,
         fmt::join(unsupported, ", "));
  return model;
}

// ---------------------------------------------------------------------------------------------
// Checked access to buffers

// Everything the conversion shares: the model, the scene being built and what was converted.
struct Context {
  Context(const std::string& p, const tg::Model& m, Scene& s) : path(p), model(m), scene(s) {}

  const std::string& path;
  const tg::Model& model;
  Scene& scene;
  std::vector<int> material_of;   // glTF material -> scene material (-1: not yet converted)
  int default_material = -1;      // for primitives without a material
  std::map<int, int> texture_of;  // glTF image -> scene texture (-1: unusable)
  std::set<std::string> ignored;  // unsupported features met, reported once
  std::set<int> skipped_modes;    // primitive modes other than triangles, reported once
  bool camera_found = false;
  // What the node walk produced, per glTF node (for animations): whether the node was reached,
  // its parent (-1 for a root), its world transform and the scene meshes and lights it made
  // ([first, end) ranges; a node's primitives and its light are consecutive).
  std::vector<char> visited;
  std::vector<int> parent_of;
  std::vector<mat4> world_of;
  std::vector<std::pair<uint32_t, uint32_t>> meshes_of, lights_of;
  std::vector<int> walk_order;  // visited nodes, parents first
};

struct Bytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
};

// The bytes of a bufferView after checking that it lies inside its buffer.
Bytes buffer_view_bytes(const Context& ctx, int index, const std::string& what) {
  const tg::Model& m = ctx.model;
  if (index < 0 || size_t(index) >= m.bufferViews.size())
    fail("{}: {}: bufferView {} does not exist ({} bufferViews)", ctx.path, what, index,
         m.bufferViews.size());
  const tg::BufferView& view = m.bufferViews[size_t(index)];
  if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
    fail("{}: {}: bufferView {} uses buffer {}, which does not exist ({} buffers)", ctx.path, what,
         index, view.buffer, m.buffers.size());
  const std::vector<unsigned char>& data = m.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("{}: {}: bufferView {} (offset {}, length {}) runs past the end of buffer {} ({} bytes)",
         ctx.path, what, index, view.byteOffset, view.byteLength, view.buffer, data.size());
  return {data.data() + view.byteOffset, view.byteLength};
}

// A checked accessor: `count` elements of `components` values, `stride` bytes apart.
struct AccessorData {
  const unsigned char* data = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    default:
      return "matrix or unknown";
  }
}

AccessorData accessor_data(const Context& ctx, int index, const std::string& what) {
  const tg::Model& m = ctx.model;
  if (index < 0 || size_t(index) >= m.accessors.size())
    fail("{}: {}: accessor {} does not exist ({} accessors)", ctx.path, what, index,
         m.accessors.size());
  const tg::Accessor& a = m.accessors[size_t(index)];
  const std::string where = fmt::format("{} (accessor {})", what, index);
  if (a.sparse.isSparse) fail("{}: {}: sparse accessors are not supported", ctx.path, where);
  const int component_size = tg::GetComponentSizeInBytes(uint32_t(a.componentType));
  const int components = tg::GetNumComponentsInType(uint32_t(a.type));
  if (component_size <= 0)
    fail("{}: {}: unknown component type {}", ctx.path, where, a.componentType);
  if (components <= 0) fail("{}: {}: unknown type {}", ctx.path, where, a.type);
  if (a.bufferView < 0) fail("{}: {}: has no bufferView", ctx.path, where);
  const Bytes view = buffer_view_bytes(ctx, a.bufferView, where);
  const size_t element = size_t(component_size) * size_t(components);
  const size_t declared_stride = m.bufferViews[size_t(a.bufferView)].byteStride;
  const size_t stride = declared_stride != 0 ? declared_stride : element;
  if (stride < element)
    fail("{}: {}: byteStride {} is smaller than an element ({} bytes)", ctx.path, where, stride,
         element);
  AccessorData out;
  out.count = a.count;
  out.stride = stride;
  out.component_type = a.componentType;
  out.components = components;
  out.normalized = a.normalized;
  if (a.count == 0) return out;
  // The last element must end inside the view: offset + stride * (count - 1) + element <= length,
  // checked without overflow.
  const bool fits = a.byteOffset <= view.size && element <= view.size - a.byteOffset &&
                    a.count - 1 <= (view.size - a.byteOffset - element) / stride;
  if (!fits)
    fail(
        "{}: {}: {} elements of {} bytes (stride {}) from byte offset {} run past the end of "
        "bufferView {} ({} bytes)",
        ctx.path, where, a.count, element, stride, a.byteOffset, a.bufferView, view.size);
  out.data = view.data + a.byteOffset;
  return out;
}

void expect_type(const Context& ctx, int index, const AccessorData& a, int components,
                 const char* type, const std::string& what) {
  if (a.components != components)
    fail("{}: {}: expected {} elements, found {}", ctx.path, what, type,
         type_name(ctx.model.accessors[size_t(index)].type));
}

template <typename T>
T read_at(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));  // accessors need not be aligned
  return value;
}

std::vector<vec3> read_vec3(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 3, "VEC3", what);
  if (a.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail("{}: {}: expected float components (type {})", ctx.path, what, a.component_type);
  std::vector<vec3> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    out[i] = vec3(read_at<float>(p), read_at<float>(p + 4), read_at<float>(p + 8));
  }
  return out;
}

std::vector<vec2> read_uv(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 2, "VEC2", what);
  const int t = a.component_type;
  if (t != TINYGLTF_COMPONENT_TYPE_FLOAT &&
      !(a.normalized && (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)))
    fail("{}: {}: texture coordinates must be float or normalized unsigned byte/short", ctx.path,
         what);
  std::vector<vec2> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    if (t == TINYGLTF_COMPONENT_TYPE_FLOAT) {
      out[i] = vec2(read_at<float>(p), read_at<float>(p + 4));
    } else if (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      out[i] = vec2(p[0], p[1]) / 255.0f;
    } else {
      out[i] = vec2(read_at<uint16_t>(p), read_at<uint16_t>(p + 2)) / 65535.0f;
    }
  }
  return out;
}

std::vector<uint32_t> read_indices(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 1, "SCALAR", what);
  std::vector<uint32_t> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    switch (a.component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[i] = p[0];
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        out[i] = read_at<uint16_t>(p);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        out[i] = read_at<uint32_t>(p);
        break;
      default:
        fail("{}: {}: indices must be unsigned byte, short or int (type {})", ctx.path, what,
             a.component_type);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Images and materials

// Converts a decoded 8- or 16-bit image (1 to 4 channels, sRGB) to a linear RGB texture.
bool texture_from_image(const tg::Image& image, Texture* out) {
  if (image.width <= 0 || image.height <= 0 || image.component < 1 || image.component > 4 ||
      (image.bits != 8 && image.bits != 16))
    return false;
  const size_t pixels = size_t(image.width) * size_t(image.height);
  const size_t bytes_per_pixel = size_t(image.component) * size_t(image.bits / 8);
  if (image.image.size() / bytes_per_pixel < pixels ||
      image.image.size() != pixels * bytes_per_pixel)
    return false;
  std::array<float, 256> lut;
  for (int i = 0; i < 256; ++i) lut[size_t(i)] = srgb_decode(float(i) / 255.0f);
  auto channel = [&](size_t pixel, int c) {
    const size_t at = pixel * size_t(image.component) + size_t(c);
    if (image.bits == 8) return lut[image.image[at]];
    return srgb_decode(float(read_at<uint16_t>(&image.image[2 * at])) / 65535.0f);
  };
  out->width = image.width;
  out->height = image.height;
  out->texels.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    if (image.component < 3) {  // grey or grey + alpha
      out->texels[p] = vec3(channel(p, 0));
    } else {
      out->texels[p] = vec3(channel(p, 0), channel(p, 1), channel(p, 2));
    }
  }
  return true;
}

// The scene texture for a glTF image, or -1 (with a warning) when it is missing or unreadable.
int texture_for_image(Context& ctx, int index, const std::string& material) {
  if (const auto it = ctx.texture_of.find(index); it != ctx.texture_of.end()) return it->second;
  const tg::Image& source = ctx.model.images[size_t(index)];
  const std::string label = !source.uri.empty()    ? source.uri
                            : !source.name.empty() ? source.name
                                                   : fmt::format("image {}", index);
  tg::Image decoded;
  const tg::Image* image = &source;
  if (source.image.empty() && source.bufferView >= 0) {
    const Bytes bytes = buffer_view_bytes(ctx, source.bufferView, "image '" + label + "'");
    std::string error, warnings;
    decoded.name = source.name;
    if (bytes.size > 0 && bytes.size <= size_t(INT32_MAX) &&
        tg::LoadImageData(&decoded, index, &error, &warnings, 0, 0, bytes.data, int(bytes.size),
                          nullptr))
      image = &decoded;
  }
  Texture texture;
  texture.name = label;
  int result = -1;
  if (!image->image.empty() && texture_from_image(*image, &texture)) {
    result = int(ctx.scene.textures.size());
    ctx.scene.textures.push_back(std::move(texture));
  } else {
    warn(
        fmt::format("{}: material '{}': image '{}' is missing or cannot be decoded; using the "
                    "base colour factor alone",
                    ctx.path, material, label));
  }
  ctx.texture_of[index] = result;
  return result;
}

double number_or(const tg::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tg::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

const tg::Value* extension(const tg::ExtensionMap& extensions, const char* name) {
  const auto it = extensions.find(name);
  return it != extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

vec3 vec3_from(const Context& ctx, const std::vector<double>& v, size_t min_size,
               const std::string& what) {
  if (v.size() < 3 || v.size() < min_size)
    fail("{}: {} needs {} numbers, found {}", ctx.path, what, std::max<size_t>(3, min_size),
         v.size());
  const vec3 out(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
  if (!is_finite(out)) fail("{}: {} is not finite", ctx.path, what);
  return out;
}

float finite_number(const Context& ctx, double value, const std::string& what) {
  if (!std::isfinite(value)) fail("{}: {} is not finite", ctx.path, what);
  return float(value);
}

// Metallic-roughness -> our Lambert + GGX material: a metal's base colour is its specular
// colour, a dielectric's is its diffuse albedo with F0 = 0.04 (scaled by KHR_materials_specular).
Material convert_material(Context& ctx, int index) {
  const tg::Material& m = ctx.model.materials[size_t(index)];
  Material out;
  out.name = m.name.empty() ? fmt::format("material{}", index) : m.name;
  const std::string where = "material '" + out.name + "'";
  const tg::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  const vec3 base =
      glm::clamp(vec3_from(ctx, pbr.baseColorFactor, 4, where + " baseColorFactor"), 0.0f, 1.0f);
  const float metallic =
      glm::clamp(finite_number(ctx, pbr.metallicFactor, where + " metallicFactor"), 0.0f, 1.0f);
  out.roughness =
      glm::clamp(finite_number(ctx, pbr.roughnessFactor, where + " roughnessFactor"), 0.0f, 1.0f);

  float specular = 1.0f;
  vec3 specular_colour(1.0f);
  if (const tg::Value* ext = extension(m.extensions, "KHR_materials_specular")) {
    specular =
        finite_number(ctx, number_or(*ext, "specularFactor", 1.0), where + " specularFactor");
    if (ext->Has("specularColorFactor")) {
      const tg::Value& c = ext->Get("specularColorFactor");
      if (!c.IsArray() || c.ArrayLen() != 3)
        fail("{}: {} specularColorFactor needs 3 numbers", ctx.path, where);
      for (int i = 0; i < 3; ++i)
        specular_colour[i] =
            finite_number(ctx, c.Get(i).IsNumber() ? c.Get(i).GetNumberAsDouble() : NAN,
                          where + " specularColorFactor");
    }
    if (ext->Has("specularTexture") || ext->Has("specularColorTexture"))
      ctx.ignored.insert("specular textures");
  }
  const vec3 dielectric_f0 =
      glm::min(0.04f * specular_colour, vec3(1.0f)) * glm::clamp(specular, 0.0f, 1.0f);
  out.albedo = base * (1.0f - metallic);
  out.f0 = glm::mix(dielectric_f0, base, metallic);

  if (!m.emissiveFactor.empty()) {
    float strength = 1.0f;
    if (const tg::Value* ext = extension(m.extensions, "KHR_materials_emissive_strength"))
      strength =
          finite_number(ctx, number_or(*ext, "emissiveStrength", 1.0), where + " emissiveStrength");
    out.emission = vec3_from(ctx, m.emissiveFactor, 3, where + " emissiveFactor") * strength;
  }

  if (pbr.baseColorTexture.index >= 0) {
    const int t = pbr.baseColorTexture.index;
    if (size_t(t) >= ctx.model.textures.size())
      fail("{}: {} uses texture {}, which does not exist ({} textures)", ctx.path, where, t,
           ctx.model.textures.size());
    const int source = ctx.model.textures[size_t(t)].source;
    if (source < 0 || size_t(source) >= ctx.model.images.size()) {
      warn(fmt::format("{}: {}: texture {} has no usable image; using the base colour factor",
                       ctx.path, where, t));
    } else {
      out.albedo_texture = texture_for_image(ctx, source, out.name);
    }
    if (pbr.baseColorTexture.texCoord != 0)
      ctx.ignored.insert("texture coordinate sets other than 0");
    if (pbr.baseColorTexture.extensions.count("KHR_texture_transform"))
      ctx.ignored.insert("KHR_texture_transform");
  }
  if (pbr.metallicRoughnessTexture.index >= 0) ctx.ignored.insert("metallic-roughness textures");
  if (m.normalTexture.index >= 0) ctx.ignored.insert("normal maps");
  if (m.emissiveTexture.index >= 0) ctx.ignored.insert("emissive textures");
  if (m.alphaMode != "OPAQUE" && !m.alphaMode.empty()) ctx.ignored.insert("alpha modes");
  for (const auto& [name, value] : m.extensions)
    if (!kSupportedExtensions.count(name)) ctx.ignored.insert(name);
  return out;
}

uint32_t scene_material(Context& ctx, int index, const std::string& what) {
  if (index < 0) {
    if (ctx.default_material < 0) {
      Material m;
      m.name = "default";
      m.albedo = vec3(0.8f);
      ctx.default_material = int(ctx.scene.materials.size());
      ctx.scene.materials.push_back(m);
    }
    return uint32_t(ctx.default_material);
  }
  if (size_t(index) >= ctx.model.materials.size())
    fail("{}: {} uses material {}, which does not exist ({} materials)", ctx.path, what, index,
         ctx.model.materials.size());
  int& id = ctx.material_of[size_t(index)];
  if (id < 0) {
    Material m = convert_material(ctx, index);
    id = int(ctx.scene.materials.size());
    ctx.scene.materials.push_back(std::move(m));
  }
  return uint32_t(id);
}

// ---------------------------------------------------------------------------------------------
// Geometry, lights and cameras

int attribute(const tg::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

void add_primitive(Context& ctx, const tg::Primitive& p, const mat4& world, std::string name,
                   const std::string& where) {
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES) {
    if (ctx.skipped_modes.insert(p.mode).second)
      warn(fmt::format("{}: skipping primitives of mode {} (only triangles are supported)",
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

// ---------------------------------------------------------------------------------------------
// Animations

std::vector<float> read_times(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 1, "SCALAR", what);
  if (a.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail("{}: {}: key times must be floats (component type {})", ctx.path, what, a.component_type);
  std::vector<float> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    out[i] = read_at<float>(a.data + i * a.stride);
    if (!std::isfinite(out[i])) fail("{}: {}: key time {} is not finite", ctx.path, what, i);
  }
  return out;
}

// Quaternions (x, y, z, w) as floats or normalized integers, each one checked to be usable.
std::vector<quat> read_rotations(const Context& ctx, int index, const std::string& what) {
  const AccessorData a = accessor_data(ctx, index, what);
  expect_type(ctx, index, a, 4, "VEC4", what);
  const int t = a.component_type;
  const bool integer =
      t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
      t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  if (t != TINYGLTF_COMPONENT_TYPE_FLOAT && !(integer && a.normalized))
    fail("{}: {}: rotations must be floats or normalized (unsigned) bytes or shorts", ctx.path,
         what);
  std::vector<quat> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = a.data + i * a.stride;
    vec4 q;
    for (int c = 0; c < 4; ++c) {
      switch (t) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
          q[c] = read_at<float>(p + 4 * c);
          break;
        case TINYGLTF_COMPONENT_TYPE_BYTE:
          q[c] = std::max(float(read_at<int8_t>(p + c)) / 127.0f, -1.0f);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          q[c] = float(p[c]) / 255.0f;
          break;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
          q[c] = std::max(float(read_at<int16_t>(p + 2 * c)) / 32767.0f, -1.0f);
          break;
        default:
          q[c] = float(read_at<uint16_t>(p + 2 * c)) / 65535.0f;
      }
    }
    const float length = glm::length(q);
    if (!std::isfinite(length) || !(length > 1e-12f))
      fail("{}: {}: key {} is not a usable rotation quaternion", ctx.path, what, i);
    q /= length;
    out[i] = quat(q.w, q.x, q.y, q.z);  // glTF stores x, y, z, w
  }
  return out;
}

// The keys of a glTF sampler into `out`, keeping the value keys of CUBICSPLINE's
// (in-tangent, value, out-tangent) triples.
template <typename T, typename Read>
void read_sampler(Context& ctx, const tg::AnimationSampler& sampler, const std::string& where,
                  Read read, Keyframes<T>* out) {
  const bool cubic = sampler.interpolation == "CUBICSPLINE";
  if (sampler.interpolation != "LINEAR" && sampler.interpolation != "STEP" && !cubic)
    fail("{}: {}: unknown interpolation '{}' (LINEAR, STEP or CUBICSPLINE)", ctx.path, where,
         sampler.interpolation);
  std::vector<float> times = read_times(ctx, sampler.input, where + " input");
  std::vector<T> values = read(ctx, sampler.output, where + " output");
  if (times.empty()) fail("{}: {}: the sampler has no keys", ctx.path, where);
  const size_t expected = cubic ? 3 * times.size() : times.size();
  if (values.size() != expected)
    fail("{}: {}: {} key times but {} output values (expected {}{})", ctx.path, where, times.size(),
         values.size(), expected, cubic ? " for CUBICSPLINE" : "");
  if (cubic) {
    ctx.ignored.insert("CUBICSPLINE tangents (keys are interpolated linearly)");
    for (size_t i = 0; i < times.size(); ++i) values[i] = values[3 * i + 1];
    values.resize(times.size());
  }
  for (size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1]))
      fail("{}: {}: key times must increase (key {} at {} s after {} s)", ctx.path, where, i,
           times[i], times[i - 1]);
  out->times = std::move(times);
  out->values = std::move(values);
  out->step = sampler.interpolation == "STEP";
}

std::vector<vec3> read_finite_vec3(const Context& ctx, int index, const std::string& what) {
  std::vector<vec3> v = read_vec3(ctx, index, what);
  for (size_t i = 0; i < v.size(); ++i)
    if (!is_finite(v[i])) fail("{}: {}: key {} is not finite", ctx.path, what, i);
  return v;
}

// Every node animation of the file (all animations play together) as one TrsTrack per animated
// node, attached to the meshes and lights of the node and of its descendants.
void read_animations(Context& ctx) {
  const tg::Model& m = ctx.model;
  std::vector<TrsTrack> node_tracks(m.nodes.size());
  std::vector<char> animated(m.nodes.size(), 0);
  for (size_t ai = 0; ai < m.animations.size(); ++ai) {
    const tg::Animation& anim = m.animations[ai];
    const std::string label = anim.name.empty() ? fmt::format("animation {}", ai)
                                                : fmt::format("animation {} ('{}')", ai, anim.name);
    for (size_t ci = 0; ci < anim.channels.size(); ++ci) {
      const tg::AnimationChannel& channel = anim.channels[ci];
      const std::string where = fmt::format("{} channel {}", label, ci);
      if (channel.sampler < 0 || size_t(channel.sampler) >= anim.samplers.size())
        fail("{}: {}: sampler {} does not exist ({} samplers)", ctx.path, where, channel.sampler,
             anim.samplers.size());
      if (channel.target_node < 0) {
        ctx.ignored.insert("animation channels without a target node");
        continue;
      }
      if (size_t(channel.target_node) >= m.nodes.size())
        fail("{}: {}: target node {} does not exist ({} nodes)", ctx.path, where,
             channel.target_node, m.nodes.size());
      const std::string& path = channel.target_path;
      if (path == "weights") {
        ctx.ignored.insert("morph target weight animations");
        continue;
      }
      if (path != "translation" && path != "rotation" && path != "scale")
        fail("{}: {}: unknown target path '{}' (translation, rotation, scale or weights)", ctx.path,
             where, path);
      const tg::AnimationSampler& sampler = anim.samplers[size_t(channel.sampler)];
      const std::string sampler_where = fmt::format("{} sampler {}", label, channel.sampler);
      const size_t node = size_t(channel.target_node);
      TrsTrack& track = node_tracks[node];
      animated[node] = 1;
      Keyframes<vec3> vec3_keys;
      Keyframes<quat> quat_keys;
      bool taken = false;
      if (path == "rotation") {
        read_sampler(ctx, sampler, sampler_where, read_rotations, &quat_keys);
        taken = !track.rotation.empty();
        if (!taken) track.rotation = std::move(quat_keys);
      } else {
        read_sampler(ctx, sampler, sampler_where, read_finite_vec3, &vec3_keys);
        Keyframes<vec3>& keys = path == "translation" ? track.translation : track.scale;
        taken = !keys.empty();
        if (!taken) keys = std::move(vec3_keys);
      }
      if (taken)
        ctx.ignored.insert("further channels animating a node's " + path +
                           " (the first one is used)");
    }
  }

  // Tracks for the animated nodes that were reached and move a mesh or light (theirs or a
  // descendant's), in walk order; then each mesh and light takes the tracks of its animated
  // ancestors (itself included), outermost first.
  std::vector<char> drives(m.nodes.size(), 0);
  for (auto it = ctx.walk_order.rbegin(); it != ctx.walk_order.rend(); ++it) {
    const size_t i = size_t(*it);
    drives[i] |= ctx.meshes_of[i].first != ctx.meshes_of[i].second ||
                 ctx.lights_of[i].first != ctx.lights_of[i].second;
    if (ctx.parent_of[i] >= 0) drives[size_t(ctx.parent_of[i])] |= drives[i];
  }
  Animation& out = ctx.scene.animation;
  std::vector<int> track_of(m.nodes.size(), -1);
  for (int index : ctx.walk_order) {
    const size_t i = size_t(index);
    if (!animated[i] || !drives[i]) continue;
    TrsTrack& track = node_tracks[i];
    const tg::Node& node = m.nodes[i];
    track.name = node.name.empty() ? fmt::format("node {}", index) : node.name;
    const int parent = ctx.parent_of[i];
    track.pivot = parent < 0 ? mat4(1.0f) : ctx.world_of[size_t(parent)];
    track.rest = local_transform(ctx, node, index);
    if (std::abs(glm::determinant(track.rest)) < 1e-12f)
      fail("{}: node {} is animated but its transform is singular", ctx.path, index);
    track_of[i] = int(out.tracks.size());
    out.tracks.push_back(std::move(track));
  }
  if (out.tracks.empty()) return;
  for (int index : ctx.walk_order) {
    std::vector<uint32_t> chain;
    for (int n = index; n >= 0; n = ctx.parent_of[size_t(n)])
      if (track_of[size_t(n)] >= 0) chain.push_back(uint32_t(track_of[size_t(n)]));
    if (chain.empty()) continue;
    std::reverse(chain.begin(), chain.end());
    const auto [mesh_first, mesh_end] = ctx.meshes_of[size_t(index)];
    for (uint32_t k = mesh_first; k < mesh_end; ++k) {
      AnimatedMesh am;
      am.mesh = k;
      am.tracks = chain;
      out.meshes.push_back(std::move(am));
    }
    const auto [light_first, light_end] = ctx.lights_of[size_t(index)];
    for (uint32_t k = light_first; k < light_end; ++k) {
      AnimatedLight al;
      al.light = k;
      al.tracks = chain;
      out.lights.push_back(std::move(al));
    }
  }
}

}  // namespace

Scene load_gltf(const std::string& path) {
  const tg::Model model = read_model(path);
  Scene scene;
  scene.source = path;
  Context ctx{path, model, scene};
  ctx.material_of.assign(model.materials.size(), -1);
  walk_nodes(ctx);
  read_animations(ctx);
  if (!ctx.ignored.empty())
    warn(fmt::format("{}: ignoring unsupported glTF features: {}", path,
                     fmt::join(ctx.ignored, ", ")));
  return scene;
}

}  // namespace bounce
