#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bounce/scene/load.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

using scene_test::contains;
using scene_test::error_of;
using scene_test::expect_near;
using scene_test::find_mesh;
using scene_test::TempDir;

constexpr const char* kQuadObj = "o quad\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n";

TEST(LoadSceneFile, ModelsLightsAndCamera) {
  TempDir dir;
  dir.write("models/quad.obj", kQuadObj);
  const std::string path = dir.write("room.bounce.json", R"({
    "models": [
      {"file": "models/quad.obj", "translate": [10, 0, 0], "scale": 2},
      {"builtin": "cornell", "rotate": [0, 90, 0]}
    ],
    "lights": [
      {"type": "point", "name": "bulb", "position": [1, 2, 3], "intensity": [4, 5, 6]},
      {"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0], "intensity": 7,
       "inner_deg": 10, "outer_deg": 20},
      {"type": "directional", "direction": [0, -1, 0], "irradiance": [1, 1, 0.5]},
      {"type": "sphere", "position": [0, 1, 0], "radius": 0.25, "radiance": [9, 9, 9]}
    ],
    "camera": {"position": [0, 1, -5], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_deg": 50}
  })");
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.source, path);
  EXPECT_EQ(scene.triangle_count(), 2u + 32u);
  const Mesh* quad = find_mesh(scene, "quad");
  ASSERT_NE(quad, nullptr);
  // Scaled by 2, then moved by 10 in x.
  expect_near(quad->positions[2], vec3(12, 0, 2), 1e-6f);
  // The Cornell box turned 90 degrees about +y: (x, y, z) -> (z, y, -x).
  const Mesh* left = find_mesh(scene, "left");
  ASSERT_NE(left, nullptr);
  expect_near(left->positions[0], vec3(0.0f, 0.0f, -0.5528f), 1e-6f);
  ASSERT_EQ(scene.area_lights.size(), 1u);  // the Cornell light, still emissive

  ASSERT_EQ(scene.lights.size(), 4u);
  EXPECT_EQ(scene.lights[0].type, LightType::kPoint);
  EXPECT_EQ(scene.lights[0].name, "bulb");
  expect_near(scene.lights[0].position, vec3(1, 2, 3), 0.0f);
  expect_near(scene.lights[0].intensity, vec3(4, 5, 6), 0.0f);
  EXPECT_EQ(scene.lights[1].type, LightType::kSpot);
  EXPECT_EQ(scene.lights[1].name, "lights[1]");
  expect_near(scene.lights[1].direction, vec3(0, -1, 0), 0.0f);
  expect_near(scene.lights[1].intensity, vec3(7), 0.0f);
  EXPECT_NEAR(scene.lights[1].cos_inner, std::cos(glm::radians(10.0f)), 1e-6f);
  EXPECT_NEAR(scene.lights[1].cos_outer, std::cos(glm::radians(20.0f)), 1e-6f);
  EXPECT_EQ(scene.lights[2].type, LightType::kDirectional);
  expect_near(scene.lights[2].irradiance, vec3(1, 1, 0.5f), 0.0f);
  EXPECT_EQ(scene.lights[3].type, LightType::kSphere);
  EXPECT_FLOAT_EQ(scene.lights[3].radius, 0.25f);
  expect_near(scene.lights[3].radiance, vec3(9), 0.0f);

  EXPECT_TRUE(scene.has_camera);
  expect_near(scene.camera.position, vec3(0, 1, -5), 0.0f);
  expect_near(scene.camera.look_at, vec3(0, 1, 0), 0.0f);
  EXPECT_FLOAT_EQ(scene.camera.vfov_deg, 50.0f);
}

TEST(LoadSceneFile, CameraComesFromTheFirstModelThatHasOne) {
  TempDir dir;
  const std::string path =
      dir.write("c.json", R"({"models": [{"builtin": "cornell", "translate": [1, 0, 0]}]})");
  const Scene scene = load_scene(path);
  expect_near(scene.camera.position, vec3(1.278f, 0.273f, -0.8f), 1e-6f);
  EXPECT_FLOAT_EQ(scene.camera.vfov_deg, 39.3077f);
}

TEST(LoadSceneFile, UnknownKeysAreNamedWithTheirPlace) {
  TempDir dir;
  struct Case {
    const char* json;
    const char* expected;
  };
  const Case cases[] = {
      {R"({"modles": []})", "top level: unknown key 'modles'"},
      {R"({"lights": [{"type": "point", "position": [0,1,0], "intensity": 1},
                      {"type": "point", "position": [0,1,0], "colour": [1,1,1]}]})",
       "lights[1]: unknown key 'colour'"},
      {R"({"lights": [{"type": "directional", "direction": [0,-1,0], "irradiance": 1,
                       "position": [0,0,0]}]})",
       "lights[0]: unknown key 'position'"},
      {R"({"models": [{"builtin": "cornell", "rotation": [0,0,0]}]})",
       "models[0]: unknown key 'rotation'"},
      {R"({"models": [{"builtin": "cornell"}], "camera": {"position": [0,0,0],
                       "look_at": [0,0,1], "fov": 40}})",
       "camera: unknown key 'fov'"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("k.bounce.json", c.json);
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_TRUE(contains(message, path + ": " + c.expected)) << message;
  }
}

TEST(LoadSceneFile, WrongTypesLengthsAndMissingFields) {
  TempDir dir;
  struct Case {
    const char* json;
    const char* expected;
  };
  const Case cases[] = {
      {R"([1, 2])", "top level: expected an object, found array"},
      {R"({"models": {}})", "'models' must be an array"},
      {R"({"lights": [{"type": "point", "position": [0, 1], "intensity": 1}]})",
       "lights[0]: 'position' must be an array of 3 numbers"},
      {R"({"lights": [{"type": "point", "position": [0, 1, "x"], "intensity": 1}]})",
       "lights[0]: 'position' must be a number"},
      {R"({"lights": [{"type": "point", "intensity": 1}]})",
       "lights[0]: missing required key 'position'"},
      {R"({"lights": [{"position": [0, 0, 0]}]})", "lights[0]: missing required key 'type'"},
      {R"({"lights": [{"type": "area", "position": [0, 0, 0]}]})", "unknown light type 'area'"},
      {R"({"lights": [{"type": "sphere", "position": [0,0,0], "radius": -1, "radiance": 1}]})",
       "'radius' must be positive"},
      {R"({"lights": [{"type": "spot", "position": [0,0,0], "direction": [0,-1,0],
                       "intensity": 1, "inner_deg": 30, "outer_deg": 20}]})",
       "inner_deg < outer_deg"},
      {R"({"lights": [{"type": "point", "position": [0,0,0], "intensity": [1e999, 0, 0]}]})",
       "1e999"},
      {R"({"lights": [{"type": "point", "position": [0,0,0], "intensity": -1}]})",
       "must not be negative"},
      {R"({"models": [{"builtin": "cornell", "file": "x.obj"}]})",
       "give exactly one of 'file' and 'builtin'"},
      {R"({"models": [{"builtin": "cornell", "scale": 0}]})", "'scale' must not be zero"},
      {R"({"models": [{"builtin": "sponza"}]})", "'sponza' is not a built-in scene"},
      {R"({"models": [{"builtin": "cubes:abc"}]})", "models[0]: cubes:abc"},
      {R"({"models": [{"builtin": "cornell"}], "camera": {"look_at": [0,0,1]}})",
       "camera: missing required key 'position'"},
      {R"({"models": [{"builtin": "cornell"}], "camera": {"position": [0,0,0],
                       "look_at": [0,0,0]}})",
       "'look_at' equals 'position'"},
      {R"({"a": 1, "a": 2})", "duplicate key 'a'"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("t.bounce.json", c.json);
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_TRUE(contains(message, path)) << message;
    EXPECT_TRUE(contains(message, c.expected)) << c.json << " -> " << message;
  }
}

TEST(LoadSceneFile, BadJsonGivesLineAndColumn) {
  TempDir dir;
  const std::string path =
      dir.write("bad.bounce.json", "{\n  \"models\": [\n    {\"builtin\": }\n");
  const std::string message = error_of([&] { load_scene(path); });
  EXPECT_TRUE(contains(message, path + ": invalid JSON")) << message;
  EXPECT_TRUE(contains(message, "line 3")) << message;
  EXPECT_FALSE(contains(message, "[json.exception")) << message;
}

TEST(LoadSceneFile, MissingModelFileIsNamed) {
  TempDir dir;
  const std::string path =
      dir.write("m.bounce.json", R"({"models": [{"file": "nowhere/room.obj"}]})");
  const std::string message = error_of([&] { load_scene(path); });
  EXPECT_TRUE(contains(message, "models[0]: model file 'nowhere/room.obj' not found")) << message;
}

TEST(LoadSceneFile, ErrorsInsideAModelNameBothFiles) {
  TempDir dir;
  const std::string obj = dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 5\n");
  const std::string path = dir.write("m.bounce.json", R"({"models": [{"file": "broken.obj"}]})");
  const std::string message = error_of([&] { load_scene(path); });
  EXPECT_TRUE(contains(message, path + ": models[0]: ")) << message;
  EXPECT_TRUE(contains(message, "broken.obj:4")) << message;
}

TEST(LoadSceneFile, SceneFilesCannotNest) {
  TempDir dir;
  const std::string path =
      dir.write("self.bounce.json", R"({"models": [{"file": "self.bounce.json"}]})");
  const std::string message = error_of([&] { load_scene(path); });
  EXPECT_TRUE(contains(message, "cannot be used as a model")) << message;
}

TEST(LoadSceneFile, LightsOnlySceneHasNoTrianglesButLoads) {
  TempDir dir;
  const std::string path =
      dir.write("l.json", R"({"lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1}],
                   "camera": {"position": [0, 0, -1], "look_at": [0, 0, 0]}})");
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.triangle_count(), 0u);
  EXPECT_EQ(scene.lights.size(), 1u);
}

}  // namespace
}  // namespace bounce
