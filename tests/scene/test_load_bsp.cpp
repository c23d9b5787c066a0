// The Quake 3 loader on small hand-built maps: conversions, lights, the spawn camera, and clear
// errors for every kind of broken file.
#include <cmath>
#include <span>

#include <gtest/gtest.h>

#include "bounce/scene/load.h"
#include "bounce/scene/material_eval.h"
#include "bounce/scene/quake/bsp.h"
#include "bounce/scene/quake/load_quake.h"
#include "bounce/scene/quake/units.h"
#include "bounce/trace/tracer.h"
#include "bsp_build.h"
#include "scene_test_util.h"

namespace bounce::scene_test {
namespace {

using quake::QuakeMap;
using quake::QuakeOptions;

QuakeMap load(const std::string& bytes, const QuakeOptions& options = {}) {
  const auto* p = reinterpret_cast<const uint8_t*>(bytes.data());
  return quake::load_quake_bsp(std::span(p, bytes.size()), "test.bsp", options, nullptr);
}

std::string load_error(const std::string& bytes) {
  return error_of([&] { load(bytes); });
}

TEST(LoadBsp, FloorConvertsUnitsAxesAndWinding) {
  testing::internal::CaptureStderr();  // its texture is missing: a warning
  const QuakeMap map = load(BspBuild::floor().bytes());
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(warnings, "textures/test/floor")) << warnings;
  ASSERT_EQ(map.scene.meshes.size(), 1u);
  const Mesh& m = map.scene.meshes[0];
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(map.stats.faces_by_type[1], 1u);
  EXPECT_EQ(map.stats.triangles, 2u);
  // Quake (128, 128, 0) -> (x, z, -y) * 0.0254 m.
  const float s = 128.0f * 0.0254f;
  expect_near(m.positions[2], vec3(s, 0.0f, -s), 1e-6f);
  // The floor faces Quake's +z, which is our +y: the winding's normal must point up too.
  for (uint32_t t = 0; t < 2; ++t) {
    const vec3 n = glm::normalize(m.face_normal_area2(t));
    expect_near(n, vec3(0, 1, 0), 1e-6f);
  }
  expect_near(m.normals[0], vec3(0, 1, 0), 1e-6f);
  // A missing texture is grey.
  ASSERT_EQ(map.scene.materials.size(), 1u);
  expect_near(map.scene.materials[0].albedo, vec3(0.5f), 0.0f);
  EXPECT_EQ(map.scene.materials[0].albedo_texture, -1);
  EXPECT_EQ(map.stats.textures_missing, 1u);
}

TEST(LoadBsp, SkySkipAndNodrawFacesAreNotDrawn) {
  BspBuild b = BspBuild::floor();
  for (int32_t flags : {int32_t(quake::kSurfSky), int32_t(quake::kSurfNoDraw)}) {
    b.textures[0].second = {flags, 1};
    testing::internal::CaptureStderr();
    const QuakeMap map = load(b.bytes());
    testing::internal::GetCapturedStderr();
    EXPECT_TRUE(map.scene.meshes.empty()) << flags;
    EXPECT_EQ(map.stats.faces_skipped, 1u);
  }
}

TEST(LoadBsp, PointSpotAndSunLightsFollowQ3mapsScale) {
  BspBuild b = BspBuild::floor();
  b.entities +=
      "{\n\"classname\" \"light\"\n\"origin\" \"0 0 100\"\n\"light\" \"200\"\n"
      "\"_color\" \"0.5 0.25 0\"\n}\n"
      "{\n\"classname\" \"light\"\n\"origin\" \"0 0 200\"\n\"target\" \"t1\"\n\"radius\" "
      "\"48\"\n}\n"
      "{\n\"classname\" \"info_null\"\n\"targetname\" \"t1\"\n\"origin\" \"0 128 200\"\n}\n"
      "{\n\"classname\" \"light\"\n\"origin\" \"0 0 300\"\n\"target\" \"t1\"\n\"_sun\" \"1\"\n}\n"
      "{\n\"classname\" \"light\"\n\"origin\" \"5 0 0\"\n\"target\" \"nobody\"\n}\n";
  testing::internal::CaptureStderr();
  const QuakeMap map = load(b.bytes());
  testing::internal::GetCapturedStderr();
  ASSERT_EQ(map.scene.lights.size(), 4u);
  EXPECT_EQ(map.stats.point_lights, 2u);
  EXPECT_EQ(map.stats.spot_lights, 1u);
  EXPECT_EQ(map.stats.suns, 1u);

  // Point: q3map adds light * 7500 / d^2 lightmap steps; 63.75 steps is irradiance pi W/m^2.
  const Light& point = map.scene.lights[0];
  EXPECT_EQ(point.type, LightType::kPoint);
  expect_near(point.position, vec3(0.0f, 100.0f * 0.0254f, 0.0f), 1e-6f);
  const float d_units = 200.0f, d_metres = d_units * 0.0254f;
  const float q3map_steps = 200.0f * 7500.0f / (d_units * d_units);
  const float irradiance = point.intensity.x / (d_metres * d_metres);  // colour normalised: r = 1
  EXPECT_NEAR(irradiance, kPi * q3map_steps / 63.75f, 1e-3f * irradiance);
  EXPECT_NEAR(point.intensity.y / point.intensity.x, 0.5f, 1e-6f);
  EXPECT_EQ(point.intensity.z, 0.0f);

  // Spot: aimed at its target (Quake +y is our -z); cone radius (48 + 16) at 128 units.
  const Light& spot = map.scene.lights[1];
  EXPECT_EQ(spot.type, LightType::kSpot);
  expect_near(spot.direction, vec3(0, 0, -1), 1e-6f);
  EXPECT_NEAR(spot.cos_outer, std::cos(std::atan(64.0f / 128.0f)), 1e-5f);
  EXPECT_GT(spot.cos_inner, spot.cos_outer);
  EXPECT_NEAR(spot.intensity.x, quake::point_intensity(300.0f), 1e-4f);  // default value 300

  // Sun: a spot with "_sun" shines along its axis from infinitely far.
  const Light& sun = map.scene.lights[2];
  EXPECT_EQ(sun.type, LightType::kDirectional);
  expect_near(sun.direction, glm::normalize(vec3(0.0f, -100.0f, -128.0f)), 1e-5f);

  // A missing target leaves a point light, as in q3map.
  EXPECT_EQ(map.scene.lights[3].type, LightType::kPoint);
}

TEST(LoadBsp, SpawnCameraStandsAtEyeHeightAndLooksAlongItsAngle) {
  BspBuild b = BspBuild::floor();
  b.entities +=
      "{\n\"classname\" \"info_player_start\"\n\"origin\" \"1000 0 0\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"64 32 24\"\n\"angle\" \"90\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"0 0 24\"\n\"angle\" \"180\"\n}\n";
  testing::internal::CaptureStderr();
  const QuakeMap first = load(b.bytes());
  QuakeOptions second_spawn;
  second_spawn.spawn = 1;
  const QuakeMap second = load(b.bytes(), second_spawn);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(first.stats.spawn_points, 2u);  // deathmatch spawns first, the start is a fallback
  ASSERT_TRUE(first.scene.has_camera);
  const Camera& c = first.scene.camera;
  expect_near(c.position, vec3(64.0f, 24.0f + 26.0f, -32.0f) * 0.0254f, 1e-5f);
  // Yaw 90 faces Quake's +y: our -z.
  expect_near(glm::normalize(c.look_at - c.position), vec3(0, 0, -1), 1e-5f);
  // Yaw 180 faces Quake's -x, which stays -x.
  const Camera& c2 = second.scene.camera;
  expect_near(glm::normalize(c2.look_at - c2.position), vec3(-1, 0, 0), 1e-5f);

  QuakeOptions missing;
  missing.spawn = 5;
  testing::internal::CaptureStderr();
  const std::string e = error_of([&] { load(b.bytes(), missing); });
  testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(e, "spawn point 5")) << e;
}

TEST(LoadBsp, ABareBspFileLoadsThroughTheSceneSpec) {
  TempDir dir;
  const std::string path = dir.write("room.bsp", BspBuild::floor().bytes());
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(path);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(scene.triangle_count(), 2u);
  EXPECT_TRUE(scene.has_camera);  // framed from the bounds: the map has no spawn point
}

// A map whose vertices sit within 1e-38 units of the origin (the one a fuzzer found): Embree's
// high-quality builder asserted (aborting the process) on the subnormal coordinates of its
// triangles, so the tracer gives Embree zero for them.
TEST(LoadBsp, SubnormalCoordinatesBuildAnAccelerationStructure) {
  BspBuild b;
  b.textures.push_back({"", {0, 0}});
  const float tiny = 6.0e-39f, tinier = 2.8e-45f;
  const std::array<std::array<float, 3>, 13> p = {{{tiny, tiny, tiny},
                                                   {tiny * 1.004f, tiny, tiny},
                                                   {tiny, 64, 64},
                                                   {0, 96, 64},
                                                   {0, 32, 96},
                                                   {0, 64, 96},
                                                   {0, 96, 96},
                                                   {0, 0, tinier},
                                                   {9.4e-38f, 2.35e-38f, 0},
                                                   {2.4e-35f, 0, 0},
                                                   {0, 0, 0},
                                                   {0, 0, 0},
                                                   {0, 0, 0}}};
  for (const auto& q : p) b.vertices.push_back({q, {0, 0, 1}, {0, 0}});
  b.mesh_vertices = {0, 0, 1, 0, 3, 2};
  BspBuild::Face polygon;
  polygon.vertex_count = 4;
  polygon.mesh_vertex_count = 6;
  BspBuild::Face patch;
  patch.type = 2;
  patch.first_vertex = 4;
  patch.vertex_count = 9;
  patch.size = {3, 3};
  b.faces = {polygon, patch};
  TempDir dir;
  const std::string path = dir.write("tiny.bsp", b.bytes());
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(path);
  testing::internal::GetCapturedStderr();
  ASSERT_GT(scene.triangle_count(), 0u);
  const auto tracer = make_embree_tracer(scene, BuildQuality::kHigh);
  // Every ray still gets an answer: straight down through the map's origin.
  const Hit hit = tracer->intersect(Ray{vec3(0.0f, 10.0f, 0.0f), 0.0f, vec3(0.0f, -1.0f, 0.0f)});
  EXPECT_TRUE(!hit.valid() || std::isfinite(hit.t));
}

// A 2 x 2 uncompressed 24-bit TGA, top row first: red, green / blue, white.
std::string tiny_tga() {
  std::string t(18, '\0');
  t[2] = 2;   // uncompressed true colour
  t[12] = 2;  // width
  t[14] = 2;  // height
  t[16] = 24;
  t[17] = 0x20;  // rows stored top first
  const unsigned char bgr[12] = {0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255};
  t.append(reinterpret_cast<const char*>(bgr), 12);
  return t;
}

TEST(LoadBsp, MapInAnArchiveFindsItsTgaTextureAndLoadsFromASceneFile) {
  TempDir dir;
  dir.write("maps.pk3", stored_zip({{"maps/room.bsp", BspBuild::floor().bytes()}}));
  dir.write("textures.pk3", stored_zip({{"textures/test/floor.tga", tiny_tga()}}));
  const Scene direct = load_scene(dir.file("maps.pk3") + ":maps/room.bsp");
  ASSERT_EQ(direct.materials.size(), 1u);
  ASSERT_EQ(direct.materials[0].albedo_texture, 0);  // found in the sibling archive
  const Texture& t = direct.textures[0];
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 2);
  expect_near(t.texels[0], vec3(1, 0, 0), 1e-6f);  // top-left is red
  expect_near(t.texels[3], vec3(1, 1, 1), 1e-6f);

  // A scene file places the map like a model, with its archive relative to the file.
  const std::string scene_file =
      dir.write("level.bounce.json",
                R"({"models": [{"file": "maps.pk3:maps/room.bsp", "translate": [0, 1, 0],
                      "patch_level": 2}]})");
  const Scene placed = load_scene(scene_file);
  ASSERT_EQ(placed.triangle_count(), 2u);
  EXPECT_EQ(placed.materials[0].albedo_texture, 0);
  EXPECT_NEAR(placed.bounds.lo.y, 1.0f, 1e-6f);

  const std::string bad = dir.write(
      "bad.bounce.json", R"({"models": [{"builtin": "cornell", "archives": ["x.pk3"]}]})");
  const std::string e = error_of([&] { load_scene(bad); });
  EXPECT_TRUE(contains(e, "'archives' applies only to Quake 3 maps")) << e;
  const std::string missing =
      dir.write("missing.bounce.json", R"({"models": [{"file": "maps.pk3:maps/other.bsp"}]})");
  const std::string e2 = error_of([&] { load_scene(missing); });
  EXPECT_TRUE(contains(e2, "no entry 'maps/other.bsp'")) << e2;
}

// A 2 x 1 uncompressed 32-bit TGA: an opaque white texel, then a white texel of alpha `alpha`.
std::string tga_with_alpha(unsigned char alpha) {
  std::string t(18, '\0');
  t[2] = 2;
  t[12] = 2;
  t[14] = 1;
  t[16] = 32;
  t[17] = 0x20 | 8;  // rows top first, 8 alpha bits
  const unsigned char bgra[8] = {255, 255, 255, 255, 255, 255, 255, alpha};
  t.append(reinterpret_cast<const char*>(bgra), 8);
  return t;
}

// A shader stage's alphaFunc makes the surface a cut-out on its image's alpha: GE128 keeps alpha
// from 128/255, GT0 anything above 0; LT128 (which a cut-off cannot express) stays opaque.
TEST(LoadBsp, AlphaFuncShadersBecomeCutouts) {
  struct Case {
    const char* func;
    unsigned char alpha;  // of the right-hand texel
    bool has_cutout, right_is_hole;
  };
  for (const Case c :
       {Case{"GE128", 127, true, true}, Case{"GE128", 128, true, false}, Case{"GT0", 0, true, true},
        Case{"GT0", 1, true, false}, Case{"LT128", 0, false, false}}) {
    TempDir dir;
    dir.write("maps.pk3", stored_zip({{"maps/room.bsp", BspBuild::floor().bytes()}}));
    const std::string shader = fmt::format(
        "textures/test/floor\n{{\n  {{\n    map textures/test/floor.tga\n    alphaFunc {}\n  "
        "}}\n}}\n",
        c.func);
    dir.write("textures.pk3", stored_zip({{"textures/test/floor.tga", tga_with_alpha(c.alpha)},
                                          {"scripts/test.shader", shader}}));
    testing::internal::CaptureStderr();
    const Scene scene = load_scene(dir.file("maps.pk3") + ":maps/room.bsp");
    const std::string warnings = testing::internal::GetCapturedStderr();
    ASSERT_EQ(scene.materials.size(), 1u) << c.func;
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.has_cutouts(), c.has_cutout) << c.func;
    if (!c.has_cutout) {
      EXPECT_TRUE(contains(warnings, "alphaFunc LT128")) << warnings;
      continue;
    }
    ASSERT_GE(m.alpha_texture, 0);
    std::vector<TextureView> views;
    for (const Texture& t : scene.textures) views.push_back(t.view());
    const MaterialRecord record = m;
    // Texel centres: u = 0.25 is the opaque texel, u = 0.75 the other.
    EXPECT_FALSE(cut_away(record, views.data(), vec2(0.25f, 0.5f))) << c.func;
    EXPECT_EQ(cut_away(record, views.data(), vec2(0.75f, 0.5f)), c.right_is_hole)
        << c.func << " alpha " << int(c.alpha);
  }
}

// --- Malformed files: each error names the file and the lump.

TEST(LoadBsp, BadMagicVersionAndShortHeader) {
  std::string b = BspBuild::floor().bytes();
  std::string magic = b;
  magic[0] = 'X';
  EXPECT_TRUE(contains(load_error(magic), "\"IBSP\""));
  std::string version = b;
  put_i32(version, 4, 47);
  const std::string e = load_error(version);
  EXPECT_TRUE(contains(e, "test.bsp") && contains(e, "version 47")) << e;
  EXPECT_TRUE(contains(load_error(b.substr(0, 100)), "header"));
}

TEST(LoadBsp, TruncatedFileNamesTheLumpPastTheEnd) {
  const std::string b = BspBuild::floor().bytes();
  // The faces lump is the last non-empty one: cut into it.
  const int32_t faces_at = get_i32(b, lump_entry(quake::kLumpFaces));
  const std::string e = load_error(b.substr(0, size_t(faces_at) + 50));
  EXPECT_TRUE(contains(e, "test.bsp") && contains(e, "'faces'") && contains(e, "truncated")) << e;
}

TEST(LoadBsp, LumpLengthNotAWholeNumberOfRecords) {
  std::string b = BspBuild::floor().bytes();
  put_i32(b, lump_entry(quake::kLumpVertices) + 4, 44 * 4 - 1);
  const std::string e = load_error(b);
  EXPECT_TRUE(contains(e, "'vertices'") && contains(e, "44-byte records")) << e;
}

TEST(LoadBsp, NegativeOffsetIsAnError) {
  std::string b = BspBuild::floor().bytes();
  put_i32(b, lump_entry(quake::kLumpTextures), -8);
  EXPECT_TRUE(contains(load_error(b), "'textures'"));
}

TEST(LoadBsp, FaceCountsAndIndicesPastTheirLumps) {
  {  // vertex range past the vertex lump
    BspBuild b = BspBuild::floor();
    b.faces[0].vertex_count = 5;
    const std::string e = load_error(b.bytes());
    EXPECT_TRUE(contains(e, "'faces'") && contains(e, "face 0") && contains(e, "vertices")) << e;
  }
  {  // mesh vertex range past its lump
    BspBuild b = BspBuild::floor();
    b.faces[0].first_mesh_vertex = 3;
    const std::string e = load_error(b.bytes());
    EXPECT_TRUE(contains(e, "mesh vertices 3 to 9")) << e;
  }
  {  // a mesh vertex pointing outside its face
    BspBuild b = BspBuild::floor();
    b.mesh_vertices[4] = 4;
    const std::string e = load_error(b.bytes());
    EXPECT_TRUE(contains(e, "'mesh vertices'") && contains(e, "entry 4")) << e;
  }
  {  // texture index out of range
    BspBuild b = BspBuild::floor();
    b.faces[0].texture = 3;
    EXPECT_TRUE(contains(load_error(b.bytes()), "texture 3, out of range"));
  }
  {  // unknown face type
    BspBuild b = BspBuild::floor();
    b.faces[0].type = 9;
    EXPECT_TRUE(contains(load_error(b.bytes()), "unknown type 9"));
  }
  {  // a patch whose grid does not match its vertices
    BspBuild b = BspBuild::floor();
    b.faces[0].type = 2;
    b.faces[0].size = {3, 3};
    EXPECT_TRUE(contains(load_error(b.bytes()), "4 vertices for a 3 x 3 control grid"));
    b.faces[0].size = {2, 2};
    EXPECT_TRUE(contains(load_error(b.bytes()), "each side must be odd"));
  }
  {  // non-finite vertex data
    BspBuild b = BspBuild::floor();
    b.vertices[2].p[1] = std::nanf("");
    const std::string e = load_error(b.bytes());
    EXPECT_TRUE(contains(e, "'vertices'") && contains(e, "vertex 2")) << e;
  }
}

TEST(LoadBsp, EntitySyntaxErrorsNameTheLine) {
  BspBuild b = BspBuild::floor();
  b.entities = "{\n\"classname\" \"worldspawn\"\n\"message\" \"unterminated\n}\n";
  std::string e = load_error(b.bytes());
  EXPECT_TRUE(contains(e, "'entities', line 3")) << e;
  b.entities = "{\n\"classname\" \"worldspawn\"\n";
  e = load_error(b.bytes());
  EXPECT_TRUE(contains(e, "not closed")) << e;
  b.entities = "{\n\"classname\"\n}\n";
  e = load_error(b.bytes());
  EXPECT_TRUE(contains(e, "has no value")) << e;
}

}  // namespace
}  // namespace bounce::scene_test
