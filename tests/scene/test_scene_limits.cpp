// The scene's limits (scene_limits.h) hold for every way values enter a scene: loading
// (finalize), posing (animate) and edits, each failing with the element named.
#include <gtest/gtest.h>

#include <limits>

#include "bounce/core/error.h"
#include "bounce/scene/animation.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_edit.h"
#include "bounce/scene/scene_limits.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

using scene_test::contains;
using scene_test::error_of;

// One grey triangle near the origin and one point light at `light`.
Scene scene_with_light(vec3 light) {
  Scene s;
  s.source = "limits";
  s.materials.push_back(Material{});
  Mesh m;
  m.name = "tri";
  m.positions = {vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f)};
  m.triangles = {uvec3(0, 1, 2)};
  m.materials = {0};
  s.meshes.push_back(m);
  s.lights.push_back(Light::point(light, vec3(1.0f)));
  s.lights.back().name = "bulb";
  return s;
}

TEST(SceneLimits, PositionsUpToTheExtentAreAcceptedAndBeyondAreNot) {
  Scene ok = scene_with_light(vec3(kMaxSceneExtent, 0.0f, -kMaxSceneExtent));
  EXPECT_NO_THROW(ok.finalize());
  // A camera given by the file is held to the extent too.
  Scene seen = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  seen.camera.position = vec3(0.0f, 0.0f, -3e6f);
  seen.has_camera = true;
  EXPECT_TRUE(contains(error_of([&] { seen.finalize(); }),
                       "camera position (0, 0, -3000000) is outside the scene extent"));
  for (const float x : {2e18f, 1.01e6f, std::numeric_limits<float>::infinity(),
                        std::numeric_limits<float>::quiet_NaN()}) {
    Scene s = scene_with_light(vec3(0.0f, x, 0.0f));
    const std::string e = error_of([&] { s.finalize(); });
    EXPECT_TRUE(contains(e, "limits: light 0 ('bulb', point) position")) << e;
  }
  Scene far = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  far.meshes[0].positions[2] = vec3(0.0f, 0.0f, -2e18f);
  const std::string e = error_of([&] { far.finalize(); });
  EXPECT_TRUE(contains(e,
                       "limits: mesh 'tri' vertex 2 (0, 0, -2e+18) is outside the scene "
                       "extent (|coordinate| <= 1e+06 m)"))
      << e;
}

TEST(SceneLimits, EmissionAndRadiusAreBounded) {
  Scene bright = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  bright.lights[0].intensity = vec3(1e30f);
  EXPECT_TRUE(contains(error_of([&] { bright.finalize(); }),
                       "intensity (1e+30, 1e+30, 1e+30) is above the limit of 1e+20"));
  Scene dark = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  dark.lights[0].intensity = vec3(1.0f, -1.0f, 1.0f);
  EXPECT_TRUE(contains(error_of([&] { dark.finalize(); }), "point) has a negative intensity"));
  Scene glowing = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  glowing.materials[0].emission = vec3(0.0f, 1e25f, 0.0f);
  EXPECT_TRUE(contains(error_of([&] { glowing.finalize(); }), "emission"));
  Scene big = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  big.lights[0] = Light::sphere(vec3(0.0f), 2e6f, vec3(1.0f));
  EXPECT_TRUE(contains(error_of([&] { big.finalize(); }), "radius of at most 1e+06 m"));
}

TEST(SceneLimits, KeysAreCheckedAtLoadAndPosesWhenPosed) {
  // A key of 1e308 is infinite as a float.
  Scene inf = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  TrsTrack t;
  t.name = "lamp";
  t.translation.times = {0.0f, 1.0f};
  t.translation.values = {vec3(0.0f), vec3(float(1e308), 0.0f, 0.0f)};
  inf.animation.tracks = {t};
  inf.animation.lights = {AnimatedLight{0, {0}, {}, {}}};
  EXPECT_TRUE(contains(error_of([&] { inf.finalize(); }),
                       "animation 'lamp/translation': key 1 (at 1 s) has a value that is not "
                       "finite or is outside the scene extent"));

  // Keys within the extent that carry the light beyond it: refused when posed there.
  Scene far = scene_with_light(vec3(9e5f, 0.0f, 0.0f));
  t.translation.values = {vec3(0.0f), vec3(9e5f, 0.0f, 0.0f)};
  far.animation.tracks = {t};
  far.animation.lights = {AnimatedLight{0, {0}, {}, {}}};
  far.animation.loop = false;
  ASSERT_NO_THROW(far.finalize());
  EXPECT_NO_THROW(animate(far, 0.0f));
  const std::string e = error_of([&] { animate(far, 1.0f); });
  EXPECT_TRUE(contains(e, "light 0 ('bulb', point) position (1800000, 0, 0) is outside")) << e;
}

TEST(SceneLimits, EditsAreChecked) {
  Scene s = scene_with_light(vec3(0.0f, 1.0f, 0.0f));
  s.finalize();
  EXPECT_NO_THROW(move_mesh(s, 0, vec3(5e5f, 0.0f, 0.0f)));
  EXPECT_TRUE(
      contains(error_of([&] { move_mesh(s, 0, vec3(6e5f, 0.0f, 0.0f)); }), "mesh 'tri' vertex 0"));
}

}  // namespace
}  // namespace bounce
