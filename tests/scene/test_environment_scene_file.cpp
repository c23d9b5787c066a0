// The environment light in scene files, and the default sky of scenes without lights.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "environment_test_util.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

using scene_test::contains;
using scene_test::error_of;
using scene_test::TempDir;

constexpr const char* kQuadObj = "o quad\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n";

TEST(EnvironmentSceneFile, SkyColourAndMapWithIntensityAndRotation) {
  TempDir dir;
  dir.write("quad.obj", kQuadObj);
  const std::string sky = dir.write("sky.bounce.json", R"({
    "models": [{"file": "quad.obj"}],
    "lights": [{"type": "environment", "radiance": [0.2, 0.4, 0.6], "intensity": 2}]
  })");
  const Scene uniform = load_scene(sky);
  ASSERT_EQ(uniform.lights.size(), 1u);
  EXPECT_EQ(uniform.lights[0].type, LightType::kEnvironment);
  EXPECT_EQ(uniform.lights[0].radiance, vec3(0.4f, 0.8f, 1.2f));
  EXPECT_EQ(uniform.environment_map, nullptr);
  EXPECT_EQ(SceneData::from(uniform).view().environment, 0);

  Image image = scene_test::synthetic_map(8, 4);
  dir.write("maps/sky.hdr", scene_test::hdr_file(image));
  const std::string mapped = dir.write("map.bounce.json", R"({
    "models": [{"file": "quad.obj"}],
    "lights": [
      {"type": "point", "position": [0, 1, 0], "intensity": 1},
      {"type": "environment", "name": "sky", "map": "maps/sky.hdr", "intensity": 0.5,
       "rotation_deg": 90}
    ]
  })");
  const Scene scene = load_scene(mapped);
  ASSERT_EQ(scene.lights.size(), 2u);
  const Light& env = scene.lights[1];
  EXPECT_EQ(env.name, "sky");
  EXPECT_EQ(env.radiance, vec3(0.5f));
  EXPECT_NEAR(env.rotation, 0.5f * kPi, 1e-6f);
  ASSERT_NE(scene.environment_map, nullptr);
  EXPECT_EQ(scene.environment_map->width(), 8);
  // The light's power counts the map's mean: pi r^2 times 4 pi times radiance times mean.
  EXPECT_EQ(env.map_mean, scene.environment_map->mean());
  const SceneData data = SceneData::from(scene);  // the view points into it
  const SceneView view = data.view();
  EXPECT_EQ(view.environment, 1);
  EXPECT_EQ(view.environment_map.width, 8);
}

TEST(EnvironmentSceneFile, MistakesAreClearErrors) {
  TempDir dir;
  dir.write("quad.obj", kQuadObj);
  dir.write("bad.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\nshort");
  dir.write("sky.hdr", scene_test::hdr_file(scene_test::synthetic_map(4, 2)));
  struct Case {
    const char* lights;
    const char* says;
  };
  const Case cases[] = {
      {R"([{"type": "environment", "map": "nowhere.hdr"}])",
       "environment map 'nowhere.hdr' not found"},
      {R"([{"type": "environment", "map": "bad.hdr"}])", "bad.hdr: the file is truncated"},
      {R"([{"type": "environment", "map": "quad.obj"}])", "must be an .exr or .hdr file"},
      {R"([{"type": "environment", "intensity": -1}])", "'intensity' must not be negative"},
      {R"([{"type": "environment", "radiance": [1, -1, 1]}])", "'radiance' must not be negative"},
      {R"([{"type": "environment", "position": [0, 1, 0]}])", "position"},
      {R"([{"type": "environment"}, {"type": "environment", "map": "sky.hdr"}])",
       "a second environment light"},
      {R"([{"type": "environment", "radiance": 1e30}])", "above the limit"},
  };
  for (const Case& c : cases) {
    const std::string path =
        dir.write("scene.bounce.json",
                  std::string(R"({"models": [{"file": "quad.obj"}], "lights": )") + c.lights + "}");
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_TRUE(contains(message, path)) << message;
    EXPECT_TRUE(contains(message, c.says)) << c.lights << ": " << message;
  }
}

TEST(EnvironmentSceneFile, AModelWithoutLightsGetsTheDefaultSkyAndAWarning) {
  TempDir dir;
  const std::string path = dir.write("quad.obj", kQuadObj);
  testing::internal::CaptureStderr();
  const Scene scene = load_scene(path);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(contains(warnings, path)) << warnings;
  EXPECT_TRUE(contains(warnings, "no lights")) << warnings;
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::kEnvironment);
  ASSERT_NE(scene.environment_map, nullptr);
  const SceneData data = SceneData::from(scene);  // the view points into it
  const SceneView view = data.view();
  EXPECT_EQ(view.background(vec3(0, 1, 0)), vec3(kDefaultSkyRadiance));
  EXPECT_EQ(view.background(glm::normalize(vec3(1, 0.1f, 0))), vec3(kDefaultSkyRadiance));
  EXPECT_EQ(view.background(glm::normalize(vec3(0, -0.1f, -1))), vec3(kDefaultGroundRadiance));
  const float mean = 0.5f * (kDefaultSkyRadiance + kDefaultGroundRadiance);
  EXPECT_NEAR(scene.lights[0].map_mean.x, mean, 1e-5f);

  // A scene with any emitter keeps what it has, silently.
  const std::string lit =
      dir.write("lit.obj", std::string("mtllib lit.mtl\nusemtl glow\n") + kQuadObj);
  dir.write("lit.mtl", "newmtl glow\nKd 0 0 0\nKe 1 1 1\n");
  testing::internal::CaptureStderr();
  const Scene glowing = load_scene(lit);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(glowing.lights.empty());
  EXPECT_EQ(glowing.area_lights.size(), 1u);
}

}  // namespace
}  // namespace bounce
