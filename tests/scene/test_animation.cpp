// The animation model: keyframe interpolation, nested tracks against composed node transforms,
// looping and clamping, and derived data (area lights) following moved meshes.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "bounce/core/error.h"
#include "bounce/scene/animation.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_edit.h"

namespace bounce {
namespace {

constexpr float kEps = 1e-5f;

void expect_near(vec3 a, vec3 b, float eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Keyframes, InterpolateLinearlyStepAndClampAtTheEnds) {
  Keyframes<vec3> k;
  k.times = {1.0f, 3.0f};
  k.values = {vec3(0.0f), vec3(2.0f, 4.0f, -2.0f)};
  expect_near(k.sample(2.0f), vec3(1.0f, 2.0f, -1.0f));
  expect_near(k.sample(0.0f), vec3(0.0f));
  expect_near(k.sample(9.0f), vec3(2.0f, 4.0f, -2.0f));
  k.step = true;
  expect_near(k.sample(2.9f), vec3(0.0f));
  expect_near(k.sample(3.0f), vec3(2.0f, 4.0f, -2.0f));
}

TEST(Keyframes, RotationsInterpolateAlongTheShortArc) {
  Keyframes<quat> k;
  k.times = {0.0f, 1.0f};
  k.values = {quat(1.0f, 0.0f, 0.0f, 0.0f), glm::angleAxis(glm::radians(90.0f), vec3(0, 1, 0))};
  const vec3 x = k.sample(0.5f) * vec3(1.0f, 0.0f, 0.0f);
  const float s = std::sqrt(0.5f);
  expect_near(x, vec3(s, 0.0f, -s));  // +x turned 45 degrees about +y
  // The same rotation given with the opposite sign still takes the short way.
  k.values[1] = -k.values[1];
  expect_near(k.sample(0.5f) * vec3(1.0f, 0.0f, 0.0f), vec3(s, 0.0f, -s));
}

// A scene with one triangle under two animated nodes: parent (moves along x) -> child (spins
// about y, offset from the parent by 1 along z). The triangle was baked at the rest pose.
struct NestedScene {
  Scene scene;
  vec3 local[3] = {vec3(0.0f), vec3(0.5f, 0.0f, 0.0f), vec3(0.0f, 0.5f, 0.0f)};
  mat4 parent_rest = glm::translate(mat4(1.0f), vec3(2.0f, 0.0f, 0.0f));
  mat4 child_rest = glm::translate(mat4(1.0f), vec3(0.0f, 0.0f, 1.0f));

  NestedScene() {
    scene.source = "nested";
    scene.materials.push_back(Material{});
    Mesh m;
    m.name = "tri";
    for (const vec3& p : local) m.positions.push_back(vec3(parent_rest * child_rest * vec4(p, 1)));
    m.triangles = {uvec3(0, 1, 2)};
    m.materials = {0};
    scene.meshes.push_back(m);
    TrsTrack parent;
    parent.name = "parent";
    parent.rest = parent_rest;
    parent.translation.times = {0.0f, 2.0f};
    parent.translation.values = {vec3(2.0f, 0.0f, 0.0f), vec3(4.0f, 0.0f, 0.0f)};
    TrsTrack child;
    child.name = "child";
    child.pivot = parent_rest;  // the parent's world transform at rest
    child.rest = child_rest;
    child.rotation.times = {0.0f, 2.0f};
    child.rotation.values = {quat(1, 0, 0, 0), glm::angleAxis(glm::radians(120.0f), vec3(0, 1, 0))};
    scene.animation.tracks = {parent, child};
    scene.animation.meshes = {AnimatedMesh{0, {0, 1}, {}, {}}};
    scene.animation.loop = false;
    scene.finalize();
  }
  // Where the node transforms put local vertex i at time t.
  vec3 expected(int i, float t) const {
    const vec3 parent_t = glm::mix(vec3(2, 0, 0), vec3(4, 0, 0), t / 2.0f);
    const mat4 parent = glm::translate(mat4(1.0f), parent_t);
    const mat4 child = glm::translate(mat4(1.0f), vec3(0, 0, 1)) *
                       glm::rotate(mat4(1.0f), glm::radians(60.0f * t), vec3(0, 1, 0));
    return vec3(parent * child * vec4(local[i], 1.0f));
  }
};

TEST(Animation, NestedTracksEqualTheComposedNodeTransforms) {
  NestedScene n;
  for (float t : {0.0f, 0.5f, 1.0f, 1.7f}) {
    const SceneChange change = animate(n.scene, t);
    if (t > 0.0f) {
      ASSERT_EQ(change.moved_meshes, std::vector<uint32_t>{0});
    }
    for (int i = 0; i < 3; ++i)
      expect_near(n.scene.meshes[0].positions[size_t(i)], n.expected(i, t));
  }
}

TEST(Animation, AMovedMeshKeepsItsOffsetThroughLaterPoses) {
  NestedScene n;
  const SceneChange c = move_mesh(n.scene, 0, vec3(0.0f, 5.0f, 0.0f));
  EXPECT_EQ(c.moved_meshes, std::vector<uint32_t>{0});
  EXPECT_NEAR(n.scene.bounds.lo.y, 5.0f, kEps);
  animate(n.scene, 1.0f);
  for (int i = 0; i < 3; ++i)
    expect_near(n.scene.meshes[0].positions[size_t(i)], n.expected(i, 1.0f) + vec3(0, 5, 0));
}

TEST(Animation, ClampsWithoutLoopAndReportsNoChangeWhenThePoseIsTheSame) {
  NestedScene n;
  EXPECT_TRUE(animate(n.scene, 5.0f).geometry());
  for (int i = 0; i < 3; ++i)
    expect_near(n.scene.meshes[0].positions[size_t(i)], n.expected(i, 2.0f));
  EXPECT_FALSE(animate(n.scene, 7.0f).any());  // still the end pose
  n.scene.animation.loop = true;
  EXPECT_TRUE(animate(n.scene, 2.5f).geometry());  // wraps to 0.5 s
  for (int i = 0; i < 3; ++i)
    expect_near(n.scene.meshes[0].positions[size_t(i)], n.expected(i, 0.5f));
}

TEST(Animation, MovingAnEmissiveMeshMovesItsAreaLightAndTheBounds) {
  Scene s;
  s.source = "lamp";
  Material lamp;
  lamp.albedo = vec3(0.0f);
  lamp.emission = vec3(5.0f);
  s.materials.push_back(lamp);
  Mesh m;
  m.name = "lamp";
  m.positions = {vec3(0, 1, 0), vec3(1, 1, 0), vec3(0, 1, 1)};  // faces down
  m.triangles = {uvec3(0, 1, 2)};
  m.materials = {0};
  s.meshes.push_back(m);
  TrsTrack tilt;
  tilt.name = "tilt";
  tilt.rotation.times = {0.0f, 1.0f};
  tilt.rotation.values = {quat(1, 0, 0, 0), glm::angleAxis(glm::radians(180.0f), vec3(1, 0, 0))};
  s.animation.tracks = {tilt};
  s.animation.meshes = {AnimatedMesh{0, {0}, {}, {}}};
  s.animation.loop = false;
  s.finalize();
  ASSERT_EQ(s.area_lights.size(), 1u);
  expect_near(s.area_lights[0].normals[0], vec3(0, -1, 0));
  animate(s, 1.0f);  // turned upside down about x: now at y = -1, facing up
  expect_near(s.area_lights[0].normals[0], vec3(0, 1, 0));
  EXPECT_NEAR(s.bounds.hi.y, -1.0f, kEps);
  EXPECT_NEAR(s.area_lights[0].area, 0.5f, kEps);
  // An edit moves the light now and stays through later poses (the rest copy moved too).
  const SceneChange c = move_area_light(s, 0, vec3(0.0f, 0.0f, 2.0f));
  EXPECT_EQ(c.moved_meshes, std::vector<uint32_t>{0});
  EXPECT_TRUE(c.lights);
  animate(s, 0.0f);  // back to the start pose, 2 m further along +z
  expect_near(s.meshes[0].positions[0], vec3(0, 1, 2));
}

TEST(Animation, LightsFollowTheirTracks) {
  Scene s;
  s.source = "moving light";
  s.lights.push_back(Light::spot(vec3(0, 2, 0), vec3(0, -1, 0), vec3(1.0f), 10, 20));
  TrsTrack t;
  t.name = "orbit";
  t.translation.times = {0.0f, 1.0f};
  t.translation.values = {vec3(0.0f), vec3(3.0f, 0.0f, 0.0f)};
  t.rotation.times = {0.0f, 1.0f};
  t.rotation.values = {quat(1, 0, 0, 0), glm::angleAxis(glm::radians(90.0f), vec3(0, 0, 1))};
  s.animation.tracks = {t};
  s.animation.lights = {AnimatedLight{0, {0}, {}, {}}};
  s.animation.loop = false;  // (looping, t = 1 s would wrap to 0)
  s.finalize();
  const SceneChange c = animate(s, 1.0f);
  EXPECT_TRUE(c.lights);
  EXPECT_FALSE(c.geometry());
  // Rotated 90 degrees about z, then moved by +3 x: (0, 2, 0) -> (-2, 0, 0) -> (1, 0, 0).
  expect_near(s.lights[0].position, vec3(1.0f, 0.0f, 0.0f));
  expect_near(s.lights[0].direction, vec3(1.0f, 0.0f, 0.0f));
}

TEST(Animation, FinalizeRejectsKeysThatDoNotIncrease) {
  NestedScene n;
  n.scene.animation.tracks[0].translation.times = {0.0f, 0.0f};
  EXPECT_THROW(n.scene.finalize(), Error);
  NestedScene m;
  m.scene.animation.meshes[0].tracks = {7};
  EXPECT_THROW(m.scene.finalize(), Error);
}

}  // namespace
}  // namespace bounce
