#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <tiny_gltf.h>

#include "bounce/core/color.h"
#include "bounce/core/image.h"
#include "bounce/core/image_io.h"
#include "bounce/scene/load.h"
#include "gltf_build.h"
#include "gltf_export.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

namespace tg = tinygltf;
using scene_test::contains;
using scene_test::error_of;
using scene_test::expect_near;
using scene_test::find_mesh;
using scene_test::TempDir;

using gltf_build::add_data;
using gltf_build::object;

int add_positions(tg::Model& m, const std::vector<float>& xyz) {
  const int a = add_data(m, xyz, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, xyz.size() / 3);
  vec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i < xyz.size(); i += 3) {
    lo = glm::min(lo, vec3(xyz[i], xyz[i + 1], xyz[i + 2]));
    hi = glm::max(hi, vec3(xyz[i], xyz[i + 1], xyz[i + 2]));
  }
  m.accessors[size_t(a)].minValues = {lo.x, lo.y, lo.z};
  m.accessors[size_t(a)].maxValues = {hi.x, hi.y, hi.z};
  return a;
}

// One right triangle (0,0,0), (1,0,0), (0,1,0) with u16 indices, one material, one node.
tg::Model triangle_model() {
  tg::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  tg::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.attributes["POSITION"] = add_positions(m, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  p.indices = add_data(m, std::vector<uint16_t>{0, 1, 2}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                       TINYGLTF_TYPE_SCALAR, 3);
  p.material = 0;
  tg::Mesh mesh;
  mesh.name = "tri";
  mesh.primitives.push_back(p);
  m.meshes.push_back(mesh);
  tg::Material mat;
  mat.name = "grey";
  mat.pbrMetallicRoughness.baseColorFactor = {0.5, 0.5, 0.5, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  m.materials.push_back(mat);
  tg::Node node;
  node.name = "tri_node";
  node.mesh = 0;
  m.nodes.push_back(node);
  m.scenes.push_back({});
  m.scenes[0].nodes = {0};
  m.defaultScene = 0;
  return m;
}

std::string write(const tg::Model& m, const TempDir& dir, const std::string& name) {
  const std::string path = dir.file(name);
  tg::TinyGLTF writer;
  const bool binary = name.ends_with(".glb");
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&m, path, true, true, true, binary));
  return path;
}

TEST(LoadGltf, TriangleInTextAndBinaryForm) {
  TempDir dir;
  for (const char* name : {"t.gltf", "t.glb"}) {
    const Scene scene = load_scene(write(triangle_model(), dir, name));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].name, "tri");
    EXPECT_EQ(scene.meshes[0].triangles, (std::vector<uvec3>{{0, 1, 2}}));
    expect_near(scene.meshes[0].positions[1], vec3(1, 0, 0), 0.0f);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "grey");
    expect_near(scene.materials[0].albedo, vec3(0.5f), 1e-7f);
    expect_near(scene.materials[0].f0, vec3(0.04f), 1e-7f);
  }
}

TEST(LoadGltf, NodeTranslationMovesTheBounds) {
  TempDir dir;
  tg::Model m = triangle_model();
  m.nodes[0].translation = {1, 2, 3};
  const Scene scene = load_scene(write(m, dir, "moved.gltf"));
  expect_near(scene.bounds.lo, vec3(1, 2, 3), 0.0f);
  expect_near(scene.bounds.hi, vec3(2, 3, 3), 0.0f);
}

TEST(LoadGltf, NestedTransformsCompose) {
  TempDir dir;
  for (bool as_matrix : {false, true}) {
    tg::Model m = triangle_model();
    m.nodes[0].translation = {1, 0, 0};
    tg::Node parent;
    const double h = std::sqrt(0.5);
    if (as_matrix) {
      // Rotation by 90 degrees about +y, times a uniform scale of 2 (column-major).
      parent.matrix = {0, 0, -2, 0, 0, 2, 0, 0, 2, 0, 0, 0, 0, 0, 0, 1};
    } else {
      parent.rotation = {0, h, 0, h};
      parent.scale = {2, 2, 2};
    }
    parent.children = {0};
    m.nodes.push_back(parent);
    m.scenes[0].nodes = {1};
    const Scene scene = load_scene(write(m, dir, "nested.gltf"));
    // p -> R_y(90) * 2 * (p + (1, 0, 0)): (0,0,0) -> (0,0,-2), (1,0,0) -> (0,0,-4),
    // (0,1,0) -> (0,2,-2).
    const Mesh& mesh = scene.meshes[0];
    expect_near(mesh.positions[0], vec3(0, 0, -2), 1e-6f);
    expect_near(mesh.positions[1], vec3(0, 0, -4), 1e-6f);
    expect_near(mesh.positions[2], vec3(0, 2, -2), 1e-6f);
  }
}

TEST(LoadGltf, MirroringTransformKeepsFrontFaces) {
  TempDir dir;
  tg::Model m = triangle_model();
  m.nodes[0].scale = {-1, 1, 1};
  const Scene scene = load_scene(write(m, dir, "mirror.gltf"));
  // The triangle faced +z; mirrored in x it still faces +z.
  EXPECT_GT(scene.meshes[0].face_normal_area2(0).z, 0.0f);
}

TEST(LoadGltf, PunctualLights) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Light point, spot, sun;
  point.type = "point";
  point.name = "bulb";
  point.color = {1.0, 0.5, 0.25};
  point.intensity = 8.0;
  spot.type = "spot";
  spot.color = {1, 1, 1};
  spot.intensity = 2.0;
  spot.spot.innerConeAngle = 0.2;
  spot.spot.outerConeAngle = 0.5;
  sun.type = "directional";
  sun.intensity = 3.0;
  m.lights = {point, spot, sun};
  const double h = std::sqrt(0.5);
  for (int i = 0; i < 3; ++i) {
    tg::Node n;
    n.name = "light" + std::to_string(i);
    n.extensions["KHR_lights_punctual"] = object({{"light", tg::Value(i)}});
    if (i == 0) n.translation = {1, 2, 3};
    if (i == 1) {
      n.translation = {0, 5, 0};
      n.rotation = {-h, 0, 0, h};  // -90 degrees about x: local -Z points down
    }
    m.nodes.push_back(n);
    m.scenes[0].nodes.push_back(int(m.nodes.size() - 1));
  }
  const Scene scene = load_scene(write(m, dir, "lights.gltf"));
  ASSERT_EQ(scene.lights.size(), 3u);
  const Light& p = scene.lights[0];
  EXPECT_EQ(p.type, LightType::kPoint);
  EXPECT_EQ(p.name, "bulb");
  expect_near(p.position, vec3(1, 2, 3), 0.0f);
  expect_near(p.intensity, vec3(8, 4, 2), 1e-6f);  // colour x intensity, taken as W/sr
  const Light& s = scene.lights[1];
  EXPECT_EQ(s.type, LightType::kSpot);
  EXPECT_EQ(s.name, "light1");
  expect_near(s.position, vec3(0, 5, 0), 1e-6f);
  expect_near(s.direction, vec3(0, -1, 0), 1e-6f);
  expect_near(s.intensity, vec3(2), 0.0f);
  EXPECT_NEAR(s.cos_inner, std::cos(0.2f), 1e-6f);
  EXPECT_NEAR(s.cos_outer, std::cos(0.5f), 1e-6f);
  const Light& d = scene.lights[2];
  EXPECT_EQ(d.type, LightType::kDirectional);
  expect_near(d.direction, vec3(0, 0, -1), 0.0f);
  expect_near(d.irradiance, vec3(3), 0.0f);  // taken as W/m^2
}

TEST(LoadGltf, MaterialsMetallicAndEmissiveStrength) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Material& mat = m.materials[0];
  mat.pbrMetallicRoughness.metallicFactor = 0.25;
  mat.pbrMetallicRoughness.roughnessFactor = 0.3;
  mat.emissiveFactor = {1.0, 0.5, 0.25};
  mat.extensions["KHR_materials_emissive_strength"] =
      object({{"emissiveStrength", tg::Value(10.0)}});
  m.extensionsUsed = {"KHR_materials_emissive_strength"};
  const Scene scene = load_scene(write(m, dir, "emissive.glb"));
  const Material& out = scene.materials[0];
  expect_near(out.albedo, vec3(0.5f * 0.75f), 1e-6f);
  expect_near(out.f0, vec3(0.04f * 0.75f + 0.5f * 0.25f), 1e-6f);
  EXPECT_FLOAT_EQ(out.roughness, 0.3f);
  expect_near(out.emission, vec3(10, 5, 2.5), 1e-6f);
  ASSERT_EQ(scene.area_lights.size(), 1u);
  expect_near(scene.area_lights[0].radiance, vec3(10, 5, 2.5), 1e-6f);
  EXPECT_NEAR(scene.area_lights[0].area, 0.5f, 1e-6f);
}

TEST(LoadGltf, SpecularExtensionScalesDielectricF0) {
  TempDir dir;
  tg::Model m = triangle_model();
  m.materials[0].extensions["KHR_materials_specular"] =
      object({{"specularFactor", tg::Value(0.5)},
              {"specularColorFactor",
               tg::Value(tg::Value::Array{tg::Value(1.0), tg::Value(2.0), tg::Value(0.0)})}});
  const Scene scene = load_scene(write(m, dir, "specular.gltf"));
  expect_near(scene.materials[0].f0, vec3(0.02f, 0.04f, 0.0f), 1e-7f);
}

TEST(LoadGltf, FirstPerspectiveCamera) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Camera ortho, persp, other;
  ortho.type = "orthographic";
  ortho.orthographic.xmag = ortho.orthographic.ymag = 1;
  ortho.orthographic.znear = 0.1;
  ortho.orthographic.zfar = 10;
  persp.type = "perspective";
  persp.perspective.yfov = 0.8;
  persp.perspective.znear = 0.01;
  other = persp;
  other.perspective.yfov = 1.2;
  m.cameras = {ortho, persp, other};
  for (int i = 0; i < 3; ++i) {
    tg::Node n;
    n.camera = i;
    n.translation = {0, 1, 5};
    if (i == 1) n.rotation = {0, 1, 0, 0};  // half a turn about y: looks along +z
    m.nodes.push_back(n);
    m.scenes[0].nodes.push_back(int(m.nodes.size() - 1));
  }
  const Scene scene = load_scene(write(m, dir, "camera.gltf"));
  EXPECT_TRUE(scene.has_camera);
  expect_near(scene.camera.position, vec3(0, 1, 5), 0.0f);
  expect_near(scene.camera.look_at, vec3(0, 1, 6), 1e-6f);
  expect_near(scene.camera.up, vec3(0, 1, 0), 1e-6f);
  EXPECT_NEAR(scene.camera.vfov_deg, 0.8f * 180.0f / kPi, 1e-4f);
}

TEST(LoadGltf, NonIndexedPrimitivesSmallIndicesAndNormalizedUvs) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Primitive& p = m.meshes[0].primitives[0];
  p.attributes["TEXCOORD_0"] =
      add_data(m, std::vector<uint16_t>{0, 65535, 65535, 0, 0, 0},
               TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, 3);
  m.accessors.back().normalized = true;
  p.attributes["NORMAL"] = add_data(m, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1},
                                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 3);
  tg::Primitive bytes = p;  // the same triangle reversed, with u8 indices
  bytes.indices = add_data(m, std::vector<uint8_t>{2, 1, 0, 0},
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 3);
  tg::Primitive plain = p;  // no indices at all
  plain.indices = -1;
  m.meshes[0].primitives = {p, bytes, plain};
  const Scene scene = load_scene(write(m, dir, "prims.glb"));
  ASSERT_EQ(scene.meshes.size(), 3u);
  EXPECT_EQ(scene.meshes[0].name, "tri#0");
  const Mesh& a = scene.meshes[0];
  ASSERT_EQ(a.uvs.size(), 3u);
  EXPECT_FLOAT_EQ(a.uvs[0].y, 1.0f);
  EXPECT_FLOAT_EQ(a.uvs[1].x, 1.0f);
  expect_near(a.normals[2], vec3(0, 0, 1), 0.0f);
  EXPECT_EQ(scene.meshes[1].triangles, (std::vector<uvec3>{{2, 1, 0}}));
  EXPECT_EQ(scene.meshes[2].triangles, (std::vector<uvec3>{{0, 1, 2}}));
}

TEST(LoadGltf, SkipsNonTrianglePrimitivesWithAWarning) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Primitive lines = m.meshes[0].primitives[0];
  lines.mode = TINYGLTF_MODE_LINE;
  m.meshes[0].primitives.push_back(lines);
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(write(m, dir, "lines.gltf"));
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(scene.triangle_count(), 1u);
  EXPECT_TRUE(contains(warnings, "mode 1")) << warnings;
}

// Strips and fans are triangles too (glTF 2.0 section 3.7.2.1): converted with one winding.
TEST(LoadGltf, StripsAndFansBecomeTriangles) {
  TempDir dir;
  struct Case {
    int mode;
    std::vector<float> xyz;
    size_t triangles;
    float area;
    float normal_z;  // the sign every face normal shares
  };
  const Case cases[] = {
      {TINYGLTF_MODE_TRIANGLE_STRIP, {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0}, 3, 1.5f, -1.0f},
      {TINYGLTF_MODE_TRIANGLE_FAN, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, 2, 1.0f, 1.0f},
  };
  for (const Case& c : cases) {
    tg::Model m = triangle_model();
    tg::Primitive& p = m.meshes[0].primitives[0];
    p.mode = c.mode;
    p.indices = -1;
    p.attributes["POSITION"] = add_positions(m, c.xyz);
    testing::internal::CaptureStderr();
    // The loader alone: load_scene would add its warning about the default sky (no lights).
    const Scene scene = load_gltf(write(m, dir, "mode" + std::to_string(c.mode) + ".gltf"));
    const std::string warnings = testing::internal::GetCapturedStderr();
    EXPECT_EQ(warnings, "") << c.mode;
    ASSERT_EQ(scene.triangle_count(), c.triangles) << c.mode;
    const Mesh& mesh = scene.meshes[0];
    float area = 0.0f;
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      const vec3 n = mesh.face_normal_area2(t);
      EXPECT_FLOAT_EQ(n.z, c.normal_z * glm::length(n)) << c.mode << " triangle " << t;
      area += 0.5f * glm::length(n);
    }
    EXPECT_FLOAT_EQ(area, c.area) << c.mode;
  }
}

TEST(LoadGltf, TextureIsDecodedFromSrgb) {
  TempDir dir;
  Image image(2, 2, vec3(0.2f, 0.5f, 1.0f));
  image.at(1, 1) = vec3(0.0f);
  save_image(dir.file("albedo.png"), image);
  tg::Model m = triangle_model();
  tg::Image img;
  img.uri = "albedo.png";
  m.images.push_back(img);
  tg::Texture tex;
  tex.source = 0;
  m.textures.push_back(tex);
  m.materials[0].pbrMetallicRoughness.baseColorTexture.index = 0;
  const Scene scene = load_scene(write(m, dir, "textured.gltf"));
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& t = scene.textures[0];
  EXPECT_EQ(t.width, 2);
  EXPECT_EQ(t.height, 2);
  expect_near(t.texels[0], vec3(0.2f, 0.5f, 1.0f), 0.01f);
  expect_near(t.texels[3], vec3(0.0f), 0.0f);
  EXPECT_EQ(scene.materials[0].albedo_texture, 0);
}

// An image stored in a bufferView (as in .glb files) is decoded after its range is checked.
TEST(LoadGltf, ImageInABufferView) {
  TempDir dir;
  Image image(1, 2, vec3(1.0f));
  image.at(0, 1) = vec3(0.0f, 1.0f, 0.0f);
  save_image(dir.file("src.png"), image);
  const std::string png = scene_test::read_bytes(dir.file("src.png"));
  for (bool corrupt : {false, true}) {
    tg::Model m = triangle_model();
    std::vector<unsigned char>& data = m.buffers[0].data;
    tg::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = png.size();
    data.insert(data.end(), png.begin(), png.end());
    if (corrupt) view.byteLength += 100;  // runs past the end of the buffer
    m.bufferViews.push_back(view);
    tg::Image img;
    img.bufferView = int(m.bufferViews.size() - 1);
    img.mimeType = "image/png";
    m.images.push_back(img);
    tg::Texture tex;
    tex.source = 0;
    m.textures.push_back(tex);
    m.materials[0].pbrMetallicRoughness.baseColorTexture.index = 0;
    const std::string path = write(m, dir, corrupt ? "bad_view.glb" : "view.glb");
    if (corrupt) {
      const std::string message = error_of([&] { load_scene(path); });
      EXPECT_TRUE(contains(message, "runs past the end of buffer 0")) << message;
      continue;
    }
    const Scene scene = load_scene(path);
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].width, 1);
    EXPECT_EQ(scene.textures[0].height, 2);
    expect_near(scene.textures[0].texels[1], vec3(0, 1, 0), 1e-6f);
  }
}

TEST(LoadGltf, MissingImageWarnsAndFallsBackToTheFactor) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Image img;
  img.uri = "missing.png";
  m.images.push_back(img);
  tg::Texture tex;
  tex.source = 0;
  m.textures.push_back(tex);
  m.materials[0].pbrMetallicRoughness.baseColorTexture.index = 0;
  const std::string path = write(m, dir, "notex.gltf");
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(path);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(warnings, "missing.png")) << warnings;
  EXPECT_TRUE(scene.textures.empty());
  EXPECT_EQ(scene.materials[0].albedo_texture, -1);
  expect_near(scene.materials[0].albedo, vec3(0.5f), 1e-7f);
}

TEST(LoadGltf, TruncatedGlbIsAnError) {
  TempDir dir;
  const std::string full = scene_test::read_bytes(write(triangle_model(), dir, "full.glb"));
  ASSERT_GT(full.size(), 40u);
  for (size_t cut :
       {size_t(0), size_t(3), size_t(12), size_t(20), full.size() / 2, full.size() - 1}) {
    const std::string path = dir.write("cut.glb", full.substr(0, cut));
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_TRUE(contains(message, path)) << cut << ": " << message;
  }
}

TEST(LoadGltf, GlbChunkLongerThanTheFileIsRefusedBeforeAllocating) {
  // Found by fuzz_glb: a 1 KB file whose JSON chunk claims 1 GiB was zero-filled into a 1 GiB
  // string before the read failed (3 s and 1 GB per load). The claim is now checked against the
  // file's size first.
  TempDir dir;
  std::string full = scene_test::read_bytes(write(triangle_model(), dir, "full.glb"));
  ASSERT_GT(full.size(), 40u);
  const uint32_t huge = 1u << 30;
  std::memcpy(&full[12], &huge, 4);  // the first chunk's length
  const std::string path = dir.write("huge-chunk.glb", full);
  struct rusage before {};
  getrusage(RUSAGE_SELF, &before);
  const std::string message = error_of([&] { load_scene(path); });
  struct rusage after {};
  getrusage(RUSAGE_SELF, &after);
  EXPECT_TRUE(contains(message, path)) << message;
  // The process's peak resident memory (KiB) grew by far less than the claimed gigabyte.
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 256L * 1024) << message;
}

TEST(LoadGltf, BadJsonIsAnError) {
  TempDir dir;
  const std::string full = scene_test::read_bytes(write(triangle_model(), dir, "full.gltf"));
  const std::string path = dir.write("cut.gltf", full.substr(0, full.size() / 2));
  const std::string message = error_of([&] { load_scene(path); });
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, "cannot load glTF")) << message;
}

TEST(LoadGltf, IndexOutOfRangeIsAnError) {
  TempDir dir;
  tg::Model m = triangle_model();
  const tg::BufferView& view = m.bufferViews[size_t(m.accessors[1].bufferView)];
  const uint16_t seven = 7;  // the third index of three vertices
  std::memcpy(&m.buffers[0].data[view.byteOffset + 4], &seven, 2);
  const std::string path = write(m, dir, "badindex.gltf");
  const std::string message = error_of([&] { load_scene(path); });
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, "index 7")) << message;
  EXPECT_TRUE(contains(message, "out of range")) << message;
}

TEST(LoadGltf, AccessorsOutsideTheirBuffersAreErrors) {
  TempDir dir;
  {
    tg::Model m = triangle_model();
    m.accessors[0].byteOffset = 1000;  // positions start past the end of their view
    const std::string message = error_of([&] { load_scene(write(m, dir, "offset.gltf")); });
    EXPECT_TRUE(contains(message, "run past the end")) << message;
  }
  {
    tg::Model m = triangle_model();
    m.accessors[0].count = 1000;  // more elements than the view holds
    const std::string message = error_of([&] { load_scene(write(m, dir, "count.glb")); });
    EXPECT_TRUE(contains(message, "POSITION")) << message;
  }
  {
    tg::Model m = triangle_model();
    m.bufferViews[0].byteOffset = 4096;  // the view itself lies outside the buffer
    const std::string message = error_of([&] { load_scene(write(m, dir, "view.gltf")); });
    EXPECT_TRUE(contains(message, "view.gltf")) << message;
  }
  {
    tg::Model m = triangle_model();
    m.meshes[0].primitives[0].attributes["POSITION"] = 9;  // no such accessor
    const std::string message = error_of([&] { load_scene(write(m, dir, "acc.gltf")); });
    EXPECT_TRUE(contains(message, "accessor 9 does not exist")) << message;
  }
  {
    tg::Model m = triangle_model();
    m.accessors[0].componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;  // positions as u16
    const std::string message = error_of([&] { load_scene(write(m, dir, "type.gltf")); });
    EXPECT_TRUE(contains(message, "float")) << message;
  }
}

TEST(LoadGltf, NodeCycleIsAnError) {
  TempDir dir;
  tg::Model m = triangle_model();
  tg::Node other;
  other.children = {0};
  m.nodes.push_back(other);
  m.nodes[0].children = {1};
  const std::string message = error_of([&] { load_scene(write(m, dir, "cycle.gltf")); });
  EXPECT_TRUE(contains(message, "cycle.gltf")) << message;
}

TEST(LoadGltf, RequiredUnsupportedExtensionIsAnError) {
  TempDir dir;
  tg::Model m = triangle_model();
  m.extensionsUsed = {"KHR_draco_mesh_compression"};
  m.extensionsRequired = {"KHR_draco_mesh_compression"};
  const std::string message = error_of([&] { load_scene(write(m, dir, "draco.gltf")); });
  EXPECT_TRUE(contains(message, "KHR_draco_mesh_compression")) << message;
}

// The Cornell box written as glTF and read back is the same scene as the built-in one.
TEST(LoadGltf, CornellRoundTripMatchesTheObj) {
  TempDir dir;
  const Scene obj = make_cornell();
  for (bool binary : {false, true}) {
    const std::string path = dir.file(binary ? "cornell.glb" : "cornell.gltf");
    write_scene_as_gltf(obj, path, binary);
    const Scene gltf = load_scene(path);
    ASSERT_EQ(gltf.meshes.size(), obj.meshes.size());
    EXPECT_EQ(gltf.triangle_count(), 32u);
    for (size_t i = 0; i < obj.meshes.size(); ++i) {
      const Mesh& a = obj.meshes[i];
      const Mesh& b = gltf.meshes[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.positions, b.positions);
      EXPECT_EQ(a.triangles, b.triangles);
      const Material& ma = obj.materials[a.materials[0]];
      const Material& mb = gltf.materials[b.materials[0]];
      EXPECT_EQ(ma.name, mb.name);
      expect_near(mb.albedo, ma.albedo, 1e-7f);
      expect_near(mb.f0, ma.f0, 0.0f);
      expect_near(mb.emission, ma.emission, 1e-5f);
      EXPECT_NEAR(mb.roughness, ma.roughness, 1e-6f);
    }
    ASSERT_EQ(gltf.area_lights.size(), 1u);
    EXPECT_NEAR(gltf.area_lights[0].area, obj.area_lights[0].area, 1e-7f);
    expect_near(gltf.area_lights[0].radiance, vec3(17, 12, 4), 1e-5f);
    expect_near(gltf.bounds.lo, obj.bounds.lo, 0.0f);
    expect_near(gltf.bounds.hi, obj.bounds.hi, 0.0f);
    expect_near(gltf.camera.position, obj.camera.position, 1e-6f);
    expect_near(glm::normalize(gltf.camera.look_at - gltf.camera.position), vec3(0, 0, 1), 1e-6f);
    expect_near(gltf.camera.up, vec3(0, 1, 0), 1e-6f);
    EXPECT_NEAR(gltf.camera.vfov_deg, obj.camera.vfov_deg, 1e-4f);
  }
}

TEST(LoadGltf, ExportedLightsRoundTrip) {
  TempDir dir;
  Scene scene = make_leak();
  scene.lights.push_back(Light::spot(vec3(1, 2, 1), vec3(1, -1, 0), vec3(3, 2, 1), 10, 30));
  scene.lights.push_back(Light::directional(vec3(0, -1, 1), vec3(0.5f)));
  scene.lights.push_back(Light::point(vec3(0.5f, 1, 0.5f), vec3(2)));
  write_scene_as_gltf(scene, dir.file("leak.glb"), true);
  const Scene back = load_scene(dir.file("leak.glb"));
  ASSERT_EQ(back.lights.size(), 4u);
  // The sphere light becomes a point light of the same far-field intensity.
  EXPECT_EQ(back.lights[0].type, LightType::kPoint);
  expect_near(back.lights[0].intensity, vec3(50.0f * kPi * 0.01f), 1e-4f);
  expect_near(back.lights[0].position, scene.lights[0].position, 1e-6f);
  EXPECT_EQ(back.lights[1].type, LightType::kSpot);
  expect_near(back.lights[1].direction, glm::normalize(vec3(1, -1, 0)), 1e-6f);
  expect_near(back.lights[1].intensity, vec3(3, 2, 1), 1e-6f);
  EXPECT_NEAR(back.lights[1].cos_inner, std::cos(glm::radians(10.0f)), 1e-6f);
  EXPECT_NEAR(back.lights[1].cos_outer, std::cos(glm::radians(30.0f)), 1e-6f);
  EXPECT_EQ(back.lights[2].type, LightType::kDirectional);
  expect_near(back.lights[2].direction, glm::normalize(vec3(0, -1, 1)), 1e-6f);
  expect_near(back.lights[2].irradiance, vec3(0.5f), 1e-6f);
  expect_near(back.lights[3].position, vec3(0.5f, 1, 0.5f), 1e-6f);
  EXPECT_EQ(back.triangle_count(), scene.triangle_count());
}

}  // namespace
}  // namespace bounce
