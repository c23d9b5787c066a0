#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "bounce/core/color.h"
#include "bounce/core/image.h"
#include "bounce/core/image_io.h"
#include "bounce/scene/builtin_data.h"
#include "bounce/scene/load.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

using scene_test::contains;
using scene_test::error_of;
using scene_test::expect_near;
using scene_test::find_mesh;
using scene_test::TempDir;

constexpr const char* kQuad =
    "o quad\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "f 1 2 3 4\n";

TEST(LoadObj, FanTriangulatesFaces) {
  const Scene scene = load_obj_text(std::string(kQuad) +
                                        "o penta\nv 0 0 1\nv 1 0 1\nv 2 1 1\nv 1 2 1\nv 0 1 1\n"
                                        "f 5 6 7 8 9\n",
                                    "", "fan");
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].name, "quad");
  EXPECT_EQ(scene.meshes[0].triangles, (std::vector<uvec3>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(scene.meshes[1].name, "penta");
  EXPECT_EQ(scene.meshes[1].triangles, (std::vector<uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
  expect_near(scene.meshes[1].positions[2], vec3(2, 1, 1), 0.0f);
}

TEST(LoadObj, DefaultMaterialWithoutMtl) {
  const Scene scene = load_obj_text(kQuad, "", "plain");
  ASSERT_EQ(scene.materials.size(), 1u);
  expect_near(scene.materials[0].albedo, vec3(0.8f), 0.0f);
  EXPECT_EQ(scene.meshes[0].materials, (std::vector<uint32_t>{0, 0}));
}

TEST(LoadObj, DeduplicatesVertexTuples) {
  // Two triangles sharing an edge with the same normal: 4 vertices; a different normal on a
  // shared position makes a separate vertex.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\n"
      "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\nf 1//2 3//2 2//2\n";
  const Scene scene = load_obj_text(obj, "", "dedup");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& m = scene.meshes[0];
  EXPECT_EQ(m.positions.size(), 7u);  // 4 with +z, 3 with -z
  ASSERT_EQ(m.normals.size(), m.positions.size());
  EXPECT_EQ(m.triangles[0], uvec3(0, 1, 2));
  EXPECT_EQ(m.triangles[1], uvec3(0, 2, 3));
  expect_near(m.normals[4], vec3(0, 0, -1), 0.0f);
}

TEST(LoadObj, FlipsTextureCoordinatesToTopLeftOrigin) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0.25 0.1\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n";
  const Scene scene = load_obj_text(obj, "", "uv");
  const Mesh& m = scene.meshes[0];
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_FLOAT_EQ(m.uvs[0].x, 0.25f);
  EXPECT_FLOAT_EQ(m.uvs[0].y, 0.9f);
  EXPECT_FLOAT_EQ(m.uvs[1].y, 1.0f);
  EXPECT_FLOAT_EQ(m.uvs[2].y, 0.0f);
}

TEST(LoadObj, PartialNormalsAndUvsStayConsistent) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0.5 0.5\n"
      "f 1/1/1 2/1/1 3/1/1\nf 1 3 4\n";
  testing::internal::CaptureStderr();
  Scene scene = load_obj_text(obj, "", "partial");
  const std::string warnings = testing::internal::GetCapturedStderr();
  const Mesh& m = scene.meshes[0];
  EXPECT_TRUE(m.normals.empty());  // dropped: only some faces had them
  EXPECT_TRUE(contains(warnings, "only some faces have normals")) << warnings;
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  scene.finalize();
  EXPECT_EQ(scene.triangle_count(), 2u);
}

TEST(LoadObj, RelativeIndices) {
  const Scene scene = load_obj_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\n", "", "relative");
  EXPECT_EQ(scene.meshes[0].triangles, (std::vector<uvec3>{{0, 1, 2}}));
}

TEST(LoadObj, MaterialsFromMtl) {
  const std::string mtl =
      "newmtl shiny\nKd 0.5 0.25 0.125\nKs 0.04 0.04 0.04\nNs 1000\n"
      "newmtl rough\nKd 0.2 0.2 0.2\nNs 0\n"
      "newmtl lamp\nKd 0 0 0\nKe 3 2 1\n";
  const std::string obj =
      "mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "usemtl shiny\nf 1 2 3\nusemtl rough\nf 1 3 4\nusemtl lamp\nf 1 2 4\n";
  Scene scene = load_obj_text(obj, mtl, "materials");
  ASSERT_EQ(scene.materials.size(), 3u);
  const Material& shiny = scene.materials[scene.meshes[0].materials[0]];
  const Material& rough = scene.materials[scene.meshes[0].materials[1]];
  const Material& lamp = scene.materials[scene.meshes[0].materials[2]];
  EXPECT_EQ(shiny.name, "shiny");
  expect_near(shiny.albedo, vec3(0.5f, 0.25f, 0.125f), 1e-7f);
  expect_near(shiny.f0, vec3(0.04f), 1e-7f);
  // alpha = sqrt(2 / (Ns + 2)), roughness = sqrt(alpha).
  EXPECT_NEAR(shiny.roughness, std::sqrt(std::sqrt(2.0f / 1002.0f)), 1e-6f);
  EXPECT_FLOAT_EQ(rough.roughness, 1.0f);
  expect_near(lamp.emission, vec3(3, 2, 1), 0.0f);
  scene.finalize();
  ASSERT_EQ(scene.area_lights.size(), 1u);
  EXPECT_NEAR(scene.area_lights[0].area, 0.5f, 1e-6f);
}

TEST(LoadObj, MtlWithoutMtllibLineIsStillRead) {
  const Scene scene = load_obj_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n",
                                    "newmtl a\nKd 0.1 0.2 0.3\n", "inline");
  expect_near(scene.materials[scene.meshes[0].materials[0]].albedo, vec3(0.1f, 0.2f, 0.3f), 1e-7f);
}

TEST(LoadObj, FileWithMtlAndTexture) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("tex"));
  Image image(2, 1);
  image.at(0, 0) = vec3(1.0f, 0.0f, 0.0f);
  image.at(1, 0) = vec3(0.0f, 0.0f, 1.0f);
  save_image(dir.file("tex/albedo.png"), image);
  dir.write("box.mtl", "newmtl t\nKd 1 1 1\nmap_Kd tex/albedo.png\n");
  const std::string path =
      dir.write("box.obj",
                "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                "usemtl t\nf 1/1 2/2 3/3\n");
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.source, path);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].width, 2);
  EXPECT_EQ(scene.textures[0].height, 1);
  const Material& m = scene.materials[scene.meshes[0].materials[0]];
  EXPECT_EQ(m.albedo_texture, 0);
  expect_near(scene.textures[0].texels[0], vec3(1, 0, 0), 1e-3f);
  expect_near(scene.textures[0].texels[1], vec3(0, 0, 1), 1e-3f);
}

TEST(LoadObj, MissingTextureWarnsAndFallsBackToKd) {
  TempDir dir;
  dir.write("box.mtl", "newmtl t\nKd 0.3 0.6 0.9\nmap_Kd missing.png\n");
  const std::string path =
      dir.write("box.obj", "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl t\nf 1 2 3\n");
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(path);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(warnings, "missing.png")) << warnings;
  EXPECT_TRUE(scene.textures.empty());
  const Material& m = scene.materials[scene.meshes[0].materials[0]];
  EXPECT_EQ(m.albedo_texture, -1);
  expect_near(m.albedo, vec3(0.3f, 0.6f, 0.9f), 1e-7f);
}

TEST(LoadObj, MissingMtlWarnsAndUsesDefaultMaterial) {
  TempDir dir;
  const std::string path =
      dir.write("a.obj", "mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl red\nf 1 2 3\n");
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(path);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(warnings, "nothere.mtl")) << warnings;
  ASSERT_EQ(scene.materials.size(), 1u);
  expect_near(scene.materials[0].albedo, vec3(0.8f), 0.0f);
}

TEST(LoadObj, FaceIndexOutOfRangeNamesFileAndLine) {
  TempDir dir;
  const std::string path = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n");
  const std::string message = error_of([&] { load_obj(path); });
  EXPECT_TRUE(contains(message, path + ":4")) << message;
  EXPECT_TRUE(contains(message, "vertex index 9")) << message;
  EXPECT_TRUE(contains(
      error_of([] { load_obj_text("v 0 0 0\nf 1 1 1\nvn 0 0 1\nf 1//2 1//1 1//1\n", "", "n"); }),
      "n:4: normal index 2"));
  EXPECT_TRUE(contains(error_of([] { load_obj_text("v 0 0 0\nf 1/3 1/1 1/1\n", "", "t"); }),
                       "t:2: texture coordinate index 3"));
  EXPECT_TRUE(contains(error_of([] { load_obj_text("v 0 0 0\nf -2 1 1\n", "", "r"); }), "r:2"));
}

TEST(LoadObj, RejectsMalformedLines) {
  struct Case {
    const char* obj;
    const char* expected;
  };
  const Case cases[] = {
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", "o:3: a face needs at least 3 vertices"},
      {"v nan 0 0\n", "o:1: 'nan' is not a finite number"},
      {"v 0 inf 0\n", "'inf' is not a finite number"},
      {"v 0 0 1e999\n", "'1e999' is not a finite number"},
      {"v 0 0\n", "o:1: 'v' needs 3 to 7 numbers, found 2"},
      {"vn 0 0 x\n", "'x' is not a finite number"},
      {"v 0 0 0\nf 1 a 1\n", "o:2: 'a' is not a face vertex"},
      {"v 0 0 0\nf 0 1 1\n", "o:2"},  // OBJ indices start at 1
      {"# nothing\n", "no triangles"},
  };
  for (const Case& c : cases) {
    const std::string message = error_of([&] {
      Scene s = load_obj_text(c.obj, "", "o");
      s.finalize();
    });
    EXPECT_TRUE(contains(message, c.expected)) << c.obj << " -> " << message;
  }
}

TEST(LoadObj, RejectsMalformedMtl) {
  const std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n";
  EXPECT_TRUE(contains(error_of([&] { load_obj_text(obj, "newmtl a\nKd 0.5\n", "m"); }),
                       "'Kd' needs 3 numbers, found 1"));
  EXPECT_TRUE(contains(error_of([&] { load_obj_text(obj, "newmtl a\nKe 1 nan 1\n", "m"); }),
                       "'nan' is not a finite number"));
  EXPECT_TRUE(
      contains(error_of([&] { load_obj_text(obj, "newmtl a\nKe -1 0 0\n", "m").finalize(); }),
               "negative emission"));
}

TEST(LoadObj, TruncatedFilesFailCleanlyOrLoadLess) {
  // Cut the Cornell box at every byte: each prefix either loads (fewer triangles) or gives an
  // Error; never a crash, a hang or another exception.
  const std::string full = builtin_data::kCornellObj;
  int errors = 0;
  testing::internal::CaptureStderr();  // cut "usemtl" lines warn about unknown materials
  for (size_t cut = 0; cut < full.size(); ++cut) {
    try {
      Scene s = load_obj_text(full.substr(0, cut), builtin_data::kCornellMtl, "cut");
      s.finalize();
      EXPECT_LE(s.triangle_count(), 32u);
    } catch (const Error&) {
      ++errors;
    }
  }
  testing::internal::GetCapturedStderr();
  EXPECT_GT(errors, 0);
  // Cut in the middle of the light's third vertex: "v 0.2130 0.54".
  const size_t at = full.find("v 0.2130 0.5487 0.3320");
  ASSERT_NE(at, std::string::npos);
  const std::string message =
      error_of([&] { load_obj_text(full.substr(0, at + 13), builtin_data::kCornellMtl, "cut"); });
  EXPECT_TRUE(contains(message, "'v' needs 3 to 7 numbers")) << message;
  // A file whose vertex list was cut short while a later face still refers to it.
  const std::string message2 =
      error_of([] { load_obj_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n", "", "short"); });
  EXPECT_TRUE(contains(message2, "short:5: vertex index 4 is out of range")) << message2;
}

TEST(LoadObj, MissingFileIsAnError) {
  const std::string message = error_of([] { load_obj("/nonexistent/dir/model.obj"); });
  EXPECT_TRUE(contains(message, "/nonexistent/dir/model.obj")) << message;
}

TEST(LoadObj, CrlfLineEndingsAndComments) {
  const Scene scene =
      load_obj_text("# c\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nf 1 2 3\r\n", "", "crlf");
  EXPECT_EQ(scene.triangle_count(), 1u);
}

}  // namespace
}  // namespace bounce
