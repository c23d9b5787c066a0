// Where a change of lights reaches direct light (render/light_change_region.h): the cones of the
// spot lights that changed, both poses, checked against the spots' own falloff at random points;
// everywhere for any other kind of change.
#include <gtest/gtest.h>

#include <vector>

#include "bounce/core/rng.h"
#include "bounce/render/light_change_region.h"
#include "bounce/scene/light.h"

namespace bounce {
namespace {

std::vector<LightRecord> records(std::initializer_list<Light> lights) {
  return std::vector<LightRecord>(lights.begin(), lights.end());
}

const Light kStill = Light::point(vec3(0.0f, 3.0f, 0.0f), vec3(5.0f));
const Light kSpot =
    Light::spot(vec3(0.0f, 1.0f, 0.0f), vec3(1.0f, -0.2f, 0.0f), vec3(20.0f), 10.0f, 20.0f);

Light turned(const Light& spot, vec3 direction) {
  Light l = spot;
  l.direction = glm::normalize(direction);
  return l;
}

TEST(LightChangeRegion, NothingChangedIsNowhere) {
  const auto lights = records({kStill, kSpot});
  const LightChangeRegion r = light_change_region(lights, lights);
  EXPECT_FALSE(r.everywhere);
  EXPECT_EQ(r.cones, 0);
  EXPECT_FALSE(r.contains(vec3(0.5f, 0.9f, 0.0f)));
}

// Every point either pose of a turned spot lights is in the region, and a point neither lights
// (the still light's alone) is not: the region is no wider than the two cones.
TEST(LightChangeRegion, ATurnedSpotReachesItsOldAndNewCones) {
  const Light moved = turned(kSpot, vec3(0.2f, -0.2f, 1.0f));
  const auto before = records({kStill, kSpot}), after = records({kStill, moved});
  const LightChangeRegion r = light_change_region(before, after);
  ASSERT_FALSE(r.everywhere);
  ASSERT_EQ(r.cones, 2);
  Pcg32 rng(5);
  int lit = 0, unlit = 0;
  for (int k = 0; k < 20000; ++k) {
    const vec3 p = vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 8.0f - 4.0f;
    const vec3 from_old = glm::normalize(p - kSpot.position);
    const vec3 from_new = glm::normalize(p - moved.position);
    const bool reached =
        spot_falloff(kSpot, from_old) > 0.0f || spot_falloff(moved, from_new) > 0.0f;
    // (Points on a cone's boundary, where the falloff is 0 and the test may say inside, are
    // measure zero.)
    EXPECT_EQ(r.contains(p), reached) << p.x << "," << p.y << "," << p.z;
    (reached ? lit : unlit) += 1;
  }
  EXPECT_GT(lit, 200);
  EXPECT_GT(unlit, 10000);
}

TEST(LightChangeRegion, ABrighterSpotReachesItsCone) {
  Light brighter = kSpot;
  brighter.intensity *= 2.0f;
  const LightChangeRegion r =
      light_change_region(records({kStill, kSpot}), records({kStill, brighter}));
  ASSERT_FALSE(r.everywhere);
  EXPECT_TRUE(r.contains(kSpot.position + 2.0f * kSpot.direction));
  EXPECT_FALSE(r.contains(kSpot.position - 2.0f * kSpot.direction));
}

// A point, directional, sphere or environment light lights everything it reaches: no cone
// bounds its change. So do a light added or removed and more changed spots than the region holds.
TEST(LightChangeRegion, OtherChangesReachEverywhere) {
  Light moved_point = kStill;
  moved_point.position.x += 0.1f;
  EXPECT_TRUE(
      light_change_region(records({kStill, kSpot}), records({moved_point, kSpot})).everywhere);
  const Light sun = Light::directional(vec3(0.0f, -1.0f, 0.0f), vec3(1.0f));
  Light turned_sun = sun;
  turned_sun.direction = glm::normalize(vec3(0.1f, -1.0f, 0.0f));
  EXPECT_TRUE(light_change_region(records({sun}), records({turned_sun})).everywhere);
  // A spot that became a point light.
  const Light bulb = Light::point(kSpot.position, kSpot.intensity);
  EXPECT_TRUE(light_change_region(records({kSpot}), records({bulb})).everywhere);
  EXPECT_TRUE(light_change_region(records({kStill}), records({kStill, kSpot})).everywhere);
  const Light t = turned(kSpot, vec3(0.0f, -1.0f, 1.0f));
  EXPECT_FALSE(light_change_region(records({kSpot, kSpot}), records({t, t})).everywhere);
  EXPECT_TRUE(light_change_region(records({kSpot, kSpot, kSpot}), records({t, t, t})).everywhere);
}

// The renderer's moved lights (moved_punctual_lights): point, spot and directional lights that
// differ, at most LightsApart::kMax of them, none after a change of the light count.
TEST(LightsApart, AreThePunctualLightsThatMoved) {
  const Light t = turned(kSpot, vec3(0.0f, -1.0f, 1.0f));
  Light moved_point = kStill;
  moved_point.position.x += 0.1f;
  const Light ball = Light::sphere(vec3(0.0f), 0.1f, vec3(1.0f));
  Light moved_ball = ball;
  moved_ball.position.y += 0.1f;
  const LightsApart a = moved_punctual_lights(records({kStill, kSpot, ball, kSpot}),
                                              records({moved_point, kSpot, moved_ball, t}));
  ASSERT_EQ(a.count, 2);
  EXPECT_EQ(a.index[0], 0u);
  EXPECT_EQ(a.index[1], 3u);
  EXPECT_EQ(moved_punctual_lights(records({kSpot}), records({kSpot})).count, 0);
  EXPECT_EQ(moved_punctual_lights(records({kSpot}), records({kSpot, t})).count, 0);
  // More than two moved: the point light first (in the history it would reach every pixel),
  // then the spot of the most power; the other spot stays in the history.
  Light dim = t, bright = t;
  dim.intensity *= 0.5f;
  bright.intensity *= 2.0f;
  const LightsApart three = moved_punctual_lights(records({kSpot, kStill, kSpot, kSpot}),
                                                  records({dim, moved_point, bright, t}));
  ASSERT_EQ(three.count, 2);
  EXPECT_EQ(three.index[0], 1u);
  EXPECT_EQ(three.index[1], 2u);
  // Spots alike: the first ones, frame after frame.
  const LightsApart alike =
      moved_punctual_lights(records({kSpot, kSpot, kSpot}), records({t, t, t}));
  ASSERT_EQ(alike.count, 2);
  EXPECT_EQ(alike.index[0], 0u);
  EXPECT_EQ(alike.index[1], 1u);
}

// The history holds the lights set apart as dark records: a spot set apart in both frames
// changes nothing there, however it moved; one that goes into the history reaches its new cone
// only, one that leaves it its old cone only; a point light going in or out reaches everywhere.
TEST(LightsApart, ReachTheHistoryOnlyWhenTheyGoInOrOut) {
  const Light t = turned(kSpot, vec3(0.0f, -1.0f, 1.0f));
  const auto before = records({kStill, kSpot}), after = records({kStill, t});
  LightsApart spot;
  spot.index[0] = 1;
  spot.count = 1;
  const auto dark_before = lights_in_history(before, spot),
             dark_after = lights_in_history(after, spot);
  EXPECT_EQ(dark_before[0], before[0]);
  EXPECT_EQ(max_component(dark_before[1].intensity), 0.0f);
  EXPECT_EQ(dark_before[1].type, LightType::kSpot);
  const LightChangeRegion both = light_change_region(dark_before, dark_after);
  EXPECT_FALSE(both.everywhere);
  EXPECT_EQ(both.cones, 0);
  const vec3 in_old = kSpot.position + 2.0f * glm::normalize(kSpot.direction);
  const vec3 in_new = t.position + 2.0f * glm::normalize(t.direction);
  const LightChangeRegion in = light_change_region(dark_before, after);
  ASSERT_FALSE(in.everywhere);
  EXPECT_EQ(in.cones, 1);
  EXPECT_TRUE(in.contains(in_new));
  EXPECT_FALSE(in.contains(in_old));
  const LightChangeRegion out = light_change_region(before, dark_after);
  ASSERT_FALSE(out.everywhere);
  EXPECT_TRUE(out.contains(in_old));
  EXPECT_FALSE(out.contains(in_new));
  LightsApart point;
  point.count = 1;
  Light moved_point = kStill;
  moved_point.position.x += 0.1f;
  const auto point_before = lights_in_history(before, point);
  EXPECT_TRUE(light_change_region(point_before, before).everywhere);
  EXPECT_FALSE(
      light_change_region(point_before, lights_in_history(records({moved_point, kSpot}), point))
          .everywhere);
}

// Only a change of lights alone is narrowed: moved meshes, materials, parameters and a new scene
// reach everywhere whatever the lights did; a camera move beside it does not widen it.
TEST(LightChangeRegion, OnlyLightChangesAreNarrowed) {
  const auto before = records({kStill, kSpot});
  const auto after = records({kStill, turned(kSpot, vec3(0.0f, -1.0f, 1.0f))});
  SceneChange lights;
  lights.lights = true;
  lights.camera = true;
  EXPECT_FALSE(light_change_region(lights, before, after).everywhere);
  SceneChange meshes = lights;
  meshes.moved_meshes = {0};
  SceneChange materials = lights;
  materials.materials = true;
  SceneChange parameters = lights;
  parameters.parameters = true;
  for (const SceneChange& c : {meshes, materials, parameters, SceneChange::all()})
    EXPECT_TRUE(light_change_region(c, before, after).everywhere);
}

}  // namespace
}  // namespace bounce
