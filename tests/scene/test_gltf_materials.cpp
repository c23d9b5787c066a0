// glTF materials in full: metallic-roughness, emissive and alpha textures, KHR_texture_transform,
// read from small glTF files written here, and what the materials then are at given uvs.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "bounce/core/color.h"
#include "bounce/render/brdf.h"
#include "bounce/scene/load.h"
#include "bounce/scene/material_eval.h"
#include "gltf_build.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

namespace tg = tinygltf;
using gltf_build::add_data;
using gltf_build::object;
using gltf_build::write_png_rgba;
using scene_test::contains;
using scene_test::expect_near;
using scene_test::TempDir;

// The unit square in z = 0 facing +z, uvs in glTF's convention (v runs down the image, here
// along -y), one material with base colour factor (0.9, 0.5, 0.2).
tg::Model quad_model() {
  tg::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  tg::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  const int pos = add_data(m, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0},
                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  m.accessors[size_t(pos)].minValues = {0, 0, 0};
  m.accessors[size_t(pos)].maxValues = {1, 1, 0};
  p.attributes["POSITION"] = pos;
  p.attributes["NORMAL"] = add_data(m, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
                                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  p.attributes["TEXCOORD_0"] = add_data(m, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0},
                                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 4);
  p.indices = add_data(m, std::vector<uint16_t>{0, 1, 2, 0, 2, 3},
                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 6);
  p.material = 0;
  tg::Mesh mesh;
  mesh.name = "quad";
  mesh.primitives.push_back(p);
  m.meshes.push_back(mesh);
  tg::Material mat;
  mat.name = "textured";
  mat.pbrMetallicRoughness.baseColorFactor = {0.9, 0.5, 0.2, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  m.materials.push_back(mat);
  tg::Node node;
  node.mesh = 0;
  m.nodes.push_back(node);
  m.scenes.push_back({});
  m.scenes[0].nodes = {0};
  m.defaultScene = 0;
  return m;
}

// Writes an RGBA image next to the model and adds it as a texture; returns the texture index.
int add_texture(tg::Model& m, const TempDir& dir, const std::string& name, int width, int height,
                const std::vector<unsigned char>& rgba) {
  write_png_rgba(dir.file(name), width, height, rgba);
  tg::Image image;
  image.uri = name;
  m.images.push_back(image);
  tg::Texture texture;
  texture.source = int(m.images.size() - 1);
  m.textures.push_back(texture);
  return int(m.textures.size() - 1);
}

// Loads the model written to `name`; `warnings` gets what the loader printed.
Scene load(const tg::Model& m, const TempDir& dir, const std::string& name,
           std::string* warnings = nullptr) {
  const std::string path = dir.file(name);
  tg::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&m, path, true, true, true, false));
  testing::internal::CaptureStderr();
  Scene scene = load_scene(path);
  const std::string printed = testing::internal::GetCapturedStderr();
  if (warnings) *warnings = printed;
  return scene;
}

tg::Value transform_extension(vec2 offset, double rotation, vec2 scale, int tex_coord = -1) {
  tg::Value::Object o;
  o["offset"] =
      tg::Value(tg::Value::Array{tg::Value(double(offset.x)), tg::Value(double(offset.y))});
  o["rotation"] = tg::Value(rotation);
  o["scale"] = tg::Value(tg::Value::Array{tg::Value(double(scale.x)), tg::Value(double(scale.y))});
  if (tex_coord >= 0) o["texCoord"] = tg::Value(tex_coord);
  return tg::Value(o);
}

// A 1 x 2 metallic-roughness texture: the top texel metallic 1 and roughness 128/255, the bottom
// one metallic 0 and roughness 1 (green = roughness, blue = metallic, read linearly).
TEST(GltfMaterials, MetallicRoughnessTextureScalesMetallicAndRoughness) {
  TempDir dir;
  tg::Model m = quad_model();
  m.materials[0].pbrMetallicRoughness.metallicFactor = 1.0;
  m.materials[0].pbrMetallicRoughness.roughnessFactor = 1.0;
  m.materials[0].pbrMetallicRoughness.metallicRoughnessTexture.index =
      add_texture(m, dir, "mr.png", 1, 2, {0, 128, 255, 255, 0, 255, 0, 255});
  const Scene scene = load(m, dir, "mr.gltf");
  const Material& mat = scene.materials[0];
  ASSERT_GE(mat.metal_rough_texture, 0);
  const vec3 base(0.9f, 0.5f, 0.2f);
  const float rough = 128.0f / 255.0f;

  const MaterialPoint metal = material_at(mat, scene.textures, vec2(0.5f, 0.25f));
  expect_near(metal.albedo, vec3(0.0f), 1e-6f);
  expect_near(metal.f0, base, 1e-5f);
  EXPECT_NEAR(metal.roughness, rough, 1e-5f);
  const MaterialPoint dielectric = material_at(mat, scene.textures, vec2(0.5f, 0.75f));
  expect_near(dielectric.albedo, base, 1e-5f);
  expect_near(dielectric.f0, vec3(0.04f), 1e-6f);
  EXPECT_NEAR(dielectric.roughness, 1.0f, 1e-6f);

  // The metal texel reflects as the GGX metal BRDF of its roughness and nothing else; the
  // texture's roughness sharpens the lobe against the factor's roughness 1.
  SurfaceHit s;
  s.albedo = metal.albedo;
  s.f0 = metal.f0;
  s.roughness = metal.roughness;
  const vec3 n(0, 0, 1), wo = glm::normalize(vec3(0.3f, 0.0f, 1.0f));
  const vec3 mirror(-wo.x, -wo.y, wo.z);
  const vec3 f = eval_brdf(s, wo, mirror);
  expect_near(f, ggx_specular(n, wo, mirror, rough, base), 1e-5f);
  EXPECT_GT(f.x, 3.0f * ggx_specular(n, wo, mirror, 1.0f, base).x);
}

// KHR_texture_transform: offset and scale, and a quarter turn, each land a uv on a known texel.
TEST(GltfMaterials, TextureTransformMapsKnownTexels) {
  // Red, green / blue, white: the texel centres are at u, v = 0.25 and 0.75.
  const std::vector<unsigned char> quadrants = {255, 0, 0,   255, 0,   255, 0,   255,
                                                0,   0, 255, 255, 255, 255, 255, 255};
  struct Case {
    tg::Value extension;
    vec2 uv;
    vec3 expected;
  };
  const Case cases[] = {
      {transform_extension({0.5f, 0.5f}, 0.0, {0.5f, 0.5f}), {0.5f, 0.5f}, vec3(1.0f)},
      {transform_extension({0.0f, 0.0f}, 0.0, {2.0f, 2.0f}), {0.125f, 0.375f}, vec3(0, 0, 1)},
      // Rotation r maps (u, v) to (u cos r - v sin r, u sin r + v cos r).
      {transform_extension({0.0f, 0.0f}, M_PI / 2, {1.0f, 1.0f}), {0.25f, -0.75f}, vec3(0, 1, 0)},
  };
  for (const Case& c : cases) {
    TempDir dir;
    tg::Model m = quad_model();
    m.materials[0].pbrMetallicRoughness.baseColorFactor = {1, 1, 1, 1};
    tg::TextureInfo& info = m.materials[0].pbrMetallicRoughness.baseColorTexture;
    info.index = add_texture(m, dir, "quadrants.png", 2, 2, quadrants);
    info.extensions["KHR_texture_transform"] = c.extension;
    m.extensionsUsed.push_back("KHR_texture_transform");
    std::string warnings;
    const Scene scene = load(m, dir, "transform.gltf", &warnings);
    EXPECT_FALSE(contains(warnings, "KHR_texture_transform")) << warnings;
    expect_near(scene.albedo(scene.materials[0], c.uv), c.expected, 1e-5f);
  }
}

// The extension's texCoord overrides the texture's: set 1 is not carried (meshes hold one uv set)
// and is named in a warning, while set 1 overridden to set 0 is read without one.
TEST(GltfMaterials, TextureTransformTexCoordOverride) {
  for (const int set : {0, 1}) {
    TempDir dir;
    tg::Model m = quad_model();
    tg::TextureInfo& info = m.materials[0].pbrMetallicRoughness.baseColorTexture;
    info.index = add_texture(m, dir, "white.png", 1, 1, {255, 255, 255, 255});
    info.texCoord = 1 - set;
    info.extensions["KHR_texture_transform"] = transform_extension({0, 0}, 0.0, {1, 1}, set);
    std::string warnings;
    load(m, dir, "override.gltf", &warnings);
    EXPECT_EQ(contains(warnings, "texture coordinate sets other than 0"), set == 1) << warnings;
  }
}

// Emission is the factor times the (sRGB) texture where a ray sees it; the area light built from
// it emits the mean texel times the factor, the texture's power spread uniformly.
TEST(GltfMaterials, EmissiveTextureTimesFactor) {
  TempDir dir;
  tg::Model m = quad_model();
  m.materials[0].emissiveFactor = {1.0, 0.5, 0.25};
  m.materials[0].emissiveTexture.index =
      add_texture(m, dir, "glow.png", 1, 2, {255, 255, 255, 255, 0, 0, 0, 255});
  std::string warnings;
  const Scene scene = load(m, dir, "glow.gltf", &warnings);
  EXPECT_FALSE(contains(warnings, "emissive")) << warnings;
  const Material& mat = scene.materials[0];
  expect_near(material_at(mat, scene.textures, vec2(0.5f, 0.25f)).emission, vec3(1, 0.5f, 0.25f),
              1e-6f);
  expect_near(material_at(mat, scene.textures, vec2(0.5f, 0.75f)).emission, vec3(0.0f), 1e-6f);
  ASSERT_EQ(scene.area_lights.size(), 1u);
  expect_near(scene.area_lights[0].radiance, vec3(0.5f, 0.25f, 0.125f), 1e-6f);
}

// MASK: base colour alpha times texture alpha against alphaCutoff. BLEND: a cut at one half.
// OPAQUE: alpha ignored.
TEST(GltfMaterials, AlphaModesCutWhereAlphaIsBelowTheCutoff) {
  struct Case {
    const char* mode;
    double cutoff;
    bool left_cut, right_cut;
  };
  // Left texel alpha 1, right texel alpha 0.4; the factor's alpha is 0.8: 0.8 and 0.32.
  const Case cases[] = {{"MASK", 0.5, false, true},
                        {"MASK", 0.9, true, true},
                        {"MASK", 0.3, false, false},
                        {"BLEND", 0.9, false, true},
                        {"OPAQUE", 0.9, false, false}};
  for (const Case& c : cases) {
    TempDir dir;
    tg::Model m = quad_model();
    m.materials[0].alphaMode = c.mode;
    m.materials[0].alphaCutoff = c.cutoff;
    m.materials[0].pbrMetallicRoughness.baseColorFactor = {1, 1, 1, 0.8};
    m.materials[0].pbrMetallicRoughness.baseColorTexture.index =
        add_texture(m, dir, "leaf.png", 2, 1, {10, 200, 10, 255, 10, 200, 10, 102});
    std::string warnings;
    const Scene scene = load(m, dir, "leaf.gltf", &warnings);
    EXPECT_FALSE(contains(warnings, "alpha")) << warnings;
    const Material& mat = scene.materials[0];
    EXPECT_EQ(cut_away(mat, scene.textures, vec2(0.25f, 0.5f)), c.left_cut) << c.mode << c.cutoff;
    EXPECT_EQ(cut_away(mat, scene.textures, vec2(0.75f, 0.5f)), c.right_cut) << c.mode << c.cutoff;
    // The colour is still the texture's colour.
    expect_near(scene.albedo(mat, vec2(0.25f, 0.5f)),
                vec3(srgb_decode(10.0f / 255.0f), srgb_decode(200.0f / 255.0f),
                     srgb_decode(10.0f / 255.0f)),
                1e-5f);
  }
}

// Every supported feature at once loads without a warning; what is still unsupported (a
// specular texture) keeps its warning.
TEST(GltfMaterials, SupportedFeaturesLoadWithoutWarnings) {
  TempDir dir;
  tg::Model m = quad_model();
  tg::Material& mat = m.materials[0];
  const int tex = add_texture(m, dir, "all.png", 1, 1, {128, 128, 255, 200});
  mat.pbrMetallicRoughness.baseColorTexture.index = tex;
  mat.pbrMetallicRoughness.metallicRoughnessTexture.index = tex;
  mat.normalTexture.index = tex;
  mat.emissiveTexture.index = tex;
  mat.emissiveFactor = {0.1, 0.1, 0.1};
  mat.alphaMode = "MASK";
  mat.normalTexture.extensions["KHR_texture_transform"] =
      transform_extension({0.1f, 0.2f}, 0.3, {2, 2});
  std::string warnings;
  Scene scene = load(m, dir, "all.gltf", &warnings);
  EXPECT_EQ(warnings, "");
  EXPECT_GE(scene.materials[0].normal_texture, 0);
  EXPECT_EQ(scene.materials[0].alpha_mode, AlphaMode::kMask);

  m.materials[0].extensions["KHR_materials_specular"] =
      object({{"specularTexture", object({{"index", tg::Value(tex)}})}});
  load(m, dir, "specular.gltf", &warnings);
  EXPECT_TRUE(contains(warnings, "specular textures")) << warnings;
}

}  // namespace
}  // namespace bounce
