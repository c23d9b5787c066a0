// glTF images and materials: metallic-roughness materials (with KHR_materials_emissive_strength
// and KHR_materials_specular) converted to ours with their base colour, metallic-roughness,
// normal and emissive textures (each through KHR_texture_transform) and alpha modes.
#include <array>
#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/scene/gltf_internal.h"

namespace bounce::gltf {

namespace {

// How an image is read into a texture: colours are sRGB (base colour, emissive), data is linear
// (metallic-roughness, normal maps), alpha is the image's alpha channel in every channel.
enum class TextureKind { kColour, kLinear, kAlpha };

bool has_alpha(const tg::Image& image) {
  return image.component == 2 || image.component == 4;
}

// Converts a decoded 8- or 16-bit image (1 to 4 channels) to a texture of `kind`.
bool texture_from_image(const tg::Image& image, TextureKind kind, Texture* out) {
  if (image.width <= 0 || image.height <= 0 || image.component < 1 || image.component > 4 ||
      (image.bits != 8 && image.bits != 16))
    return false;
  if (kind == TextureKind::kAlpha && !has_alpha(image)) return false;
  const size_t pixels = size_t(image.width) * size_t(image.height);
  if (pixels > size_t(kMaxTexels)) return false;
  const size_t bytes_per_pixel = size_t(image.component) * size_t(image.bits / 8);
  if (image.image.size() / bytes_per_pixel < pixels ||
      image.image.size() != pixels * bytes_per_pixel)
    return false;
  const bool srgb = kind == TextureKind::kColour;
  std::array<float, 256> lut;
  for (int i = 0; i < 256; ++i)
    lut[size_t(i)] = srgb ? srgb_decode(float(i) / 255.0f) : float(i) / 255.0f;
  auto channel = [&](size_t pixel, int c) {
    const size_t at = pixel * size_t(image.component) + size_t(c);
    if (image.bits == 8) return lut[image.image[at]];
    const float v = float(read_at<uint16_t>(&image.image[2 * at])) / 65535.0f;
    return srgb ? srgb_decode(v) : v;
  };
  out->width = image.width;
  out->height = image.height;
  out->texels.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    if (kind == TextureKind::kAlpha) {
      out->texels[p] = vec3(channel(p, image.component - 1));
    } else if (image.component < 3) {  // grey or grey + alpha
      out->texels[p] = vec3(channel(p, 0));
    } else {
      out->texels[p] = vec3(channel(p, 0), channel(p, 1), channel(p, 2));
    }
  }
  return true;
}

// The scene texture for a glTF image read as `kind`, or -1: with a warning when the image is
// missing or unreadable, silently when an alpha texture is asked of an image without alpha.
int texture_for_image(Context& ctx, int index, TextureKind kind, const std::string& material) {
  const std::pair<int, int> key(index, int(kind));
  if (const auto it = ctx.texture_of.find(key); it != ctx.texture_of.end()) return it->second;
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
  if (!image->image.empty() && kind == TextureKind::kAlpha && !has_alpha(*image)) {
    // an opaque image: the base colour factor's alpha alone
  } else if (!image->image.empty() && texture_from_image(*image, kind, &texture)) {
    result = int(ctx.scene.textures.size());
    ctx.scene.textures.push_back(std::move(texture));
  } else if (kind != TextureKind::kAlpha) {  // the colour read warns once for the image
    warn(
        fmt::format("{}: material '{}': image '{}' is missing or cannot be decoded; using the "
                    "material's factors alone",
                    ctx.path, material, label));
  }
  ctx.texture_of[key] = result;
  return result;
}

// A texture reference's KHR_texture_transform (identity without one); overrides `tex_coord`.
TextureTransform texture_transform(const Context& ctx, const tg::ExtensionMap& extensions,
                                   const std::string& where, int& tex_coord) {
  const tg::Value* ext = extension(extensions, "KHR_texture_transform");
  if (!ext) return {};
  auto pair = [&](const char* key, vec2 fallback) {
    if (!ext->Has(key)) return fallback;
    const tg::Value& v = ext->Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      fail("{}: {} KHR_texture_transform {} needs 2 numbers", ctx.path, where, key);
    return vec2(finite_number(ctx, v.Get(0).GetNumberAsDouble(), where + " " + key),
                finite_number(ctx, v.Get(1).GetNumberAsDouble(), where + " " + key));
  };
  const vec2 offset = pair("offset", vec2(0.0f)), scale = pair("scale", vec2(1.0f));
  const float rotation =
      finite_number(ctx, number_or(*ext, "rotation", 0.0), where + " KHR_texture_transform");
  if (ext->Has("texCoord")) tex_coord = int(number_or(*ext, "texCoord", 0.0));
  return TextureTransform::from(offset, rotation, scale);
}

// One texture slot of a material: the scene texture (-1: none) and its transform.
int texture_slot(Context& ctx, int texture, int tex_coord, const tg::ExtensionMap& extensions,
                 TextureKind kind, const std::string& material, const std::string& where,
                 TextureTransform& transform) {
  if (texture < 0) return -1;
  if (size_t(texture) >= ctx.model.textures.size())
    fail("{}: {} uses texture {}, which does not exist ({} textures)", ctx.path, where, texture,
         ctx.model.textures.size());
  transform = texture_transform(ctx, extensions, where, tex_coord);
  // Meshes carry one uv set: a texture asking for another reads set 0.
  if (tex_coord != 0) ctx.ignored.insert("texture coordinate sets other than 0");
  const int source = ctx.model.textures[size_t(texture)].source;
  if (source < 0 || size_t(source) >= ctx.model.images.size()) {
    warn(fmt::format("{}: {}: texture {} has no usable image; using the material's factors",
                     ctx.path, where, texture));
    return -1;
  }
  return texture_for_image(ctx, source, kind, material);
}

// Metallic-roughness -> our Lambert + GGX material: a metal's base colour is its specular
// colour, a dielectric's is its diffuse albedo with F0 = 0.04 (scaled by KHR_materials_specular).
// Textures vary base colour, metallic and roughness per texel (material_eval.h).
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
  out.metallic_workflow = true;
  out.metallic = metallic;
  out.base_colour = base;
  out.dielectric_f0 = dielectric_f0;

  if (!m.emissiveFactor.empty()) {
    float strength = 1.0f;
    if (const tg::Value* ext = extension(m.extensions, "KHR_materials_emissive_strength"))
      strength =
          finite_number(ctx, number_or(*ext, "emissiveStrength", 1.0), where + " emissiveStrength");
    out.emission = vec3_from(ctx, m.emissiveFactor, 3, where + " emissiveFactor") * strength;
  }

  const tg::TextureInfo& colour = pbr.baseColorTexture;
  out.albedo_texture =
      texture_slot(ctx, colour.index, colour.texCoord, colour.extensions, TextureKind::kColour,
                   out.name, where + " baseColorTexture", out.albedo_transform);
  const tg::TextureInfo& mr = pbr.metallicRoughnessTexture;
  out.metal_rough_texture =
      texture_slot(ctx, mr.index, mr.texCoord, mr.extensions, TextureKind::kLinear, out.name,
                   where + " metallicRoughnessTexture", out.metal_rough_transform);
  const tg::NormalTextureInfo& normal = m.normalTexture;
  out.normal_texture =
      texture_slot(ctx, normal.index, normal.texCoord, normal.extensions, TextureKind::kLinear,
                   out.name, where + " normalTexture", out.normal_transform);
  out.normal_scale = finite_number(ctx, normal.scale, where + " normalTexture scale");
  const tg::TextureInfo& emissive = m.emissiveTexture;
  out.emission_texture = texture_slot(ctx, emissive.index, emissive.texCoord, emissive.extensions,
                                      TextureKind::kColour, out.name, where + " emissiveTexture",
                                      out.emission_transform);
  if (out.emission_texture >= 0)
    out.emission_texture_mean = mean_texel(ctx.scene.textures[size_t(out.emission_texture)]);

  if (m.alphaMode == "MASK" || m.alphaMode == "BLEND") {
    out.alpha_mode = m.alphaMode == "MASK" ? AlphaMode::kMask : AlphaMode::kBlend;
    const double alpha = pbr.baseColorFactor.size() == 4 ? pbr.baseColorFactor[3] : 1.0;
    out.alpha = glm::clamp(finite_number(ctx, alpha, where + " baseColorFactor"), 0.0f, 1.0f);
    out.alpha_cutoff = finite_number(ctx, m.alphaCutoff, where + " alphaCutoff");
    if (colour.index >= 0 && out.albedo_texture >= 0) {
      TextureTransform unused;
      out.alpha_texture = texture_slot(ctx, colour.index, colour.texCoord, colour.extensions,
                                       TextureKind::kAlpha, out.name, where, unused);
    }
  } else if (!m.alphaMode.empty() && m.alphaMode != "OPAQUE") {
    ctx.ignored.insert("alphaMode '" + m.alphaMode + "' (not OPAQUE, MASK or BLEND; opaque)");
  }
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
