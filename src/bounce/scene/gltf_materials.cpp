// glTF images and materials: metallic-roughness materials (with KHR_materials_emissive_strength
// and KHR_materials_specular) converted to ours, base colour images to linear textures.
#include <array>
#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

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

}  // namespace

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

}  // namespace bounce::gltf
