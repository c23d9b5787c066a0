// Animation as the loaders read it: glTF node animations and the scene file's "animation",
// light animation and "camera_path", posed with animate() and checked against the composed
// transforms; error cases; and a tracer refit after animate() against a fresh build.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <glm/gtc/matrix_transform.hpp>

#include "bounce/scene/animation.h"
#include "bounce/scene/load.h"
#include "bounce/trace/tracer.h"
#include "gltf_build.h"
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

int add_floats(tg::Model& m, const std::vector<float>& v, int type, int components) {
  return add_data(m, v, TINYGLTF_COMPONENT_TYPE_FLOAT, type, v.size() / size_t(components));
}

// The triangle (0,0,0), (1,0,0), (0,1,0) on node 1 ("child", translated by (0,1,0), with a
// point light), under node 0 ("parent": translation (1,0,0) and 90 degrees about +z at rest).
// Animation 0 moves the parent from (0,0,0) at 0 s to (4,0,0) at 2 s.
constexpr float kRestTriangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

tg::Model animated_model(const std::string& interpolation) {
  tg::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  tg::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.attributes["POSITION"] =
      add_floats(m, std::vector<float>(std::begin(kRestTriangle), std::end(kRestTriangle)),
                 TINYGLTF_TYPE_VEC3, 3);
  tg::Mesh mesh;
  mesh.name = "tri";
  mesh.primitives.push_back(p);
  m.meshes.push_back(mesh);
  tg::Light light;
  light.type = "point";
  light.intensity = 1.0;
  m.lights.push_back(light);
  const double h = std::sqrt(0.5);
  tg::Node parent, child;
  parent.name = "parent";
  parent.translation = {1, 0, 0};
  parent.rotation = {0, 0, h, h};
  parent.children = {1};
  child.name = "child";
  child.translation = {0, 1, 0};
  child.mesh = 0;
  child.extensions["KHR_lights_punctual"] = object({{"light", tg::Value(0)}});
  m.nodes = {parent, child};
  m.scenes.push_back({});
  m.scenes[0].nodes = {0};
  m.defaultScene = 0;
  tg::Animation anim;
  tg::AnimationSampler s;
  s.input = add_floats(m, {0, 2}, TINYGLTF_TYPE_SCALAR, 1);
  s.output = add_floats(m, {0, 0, 0, 4, 0, 0}, TINYGLTF_TYPE_VEC3, 3);
  s.interpolation = interpolation;
  anim.samplers.push_back(s);
  tg::AnimationChannel c;
  c.sampler = 0;
  c.target_node = 0;
  c.target_path = "translation";
  anim.channels.push_back(c);
  m.animations.push_back(anim);
  return m;
}

// Adds animation 1: the child turns about +y from 0 at 0 s to 120 degrees at 2 s.
void add_child_rotation(tg::Model& m) {
  const float a = glm::radians(120.0f);
  tg::Animation anim;
  tg::AnimationSampler s;
  s.input = add_floats(m, {0, 2}, TINYGLTF_TYPE_SCALAR, 1);
  s.output =
      add_floats(m, {0, 0, 0, 1, 0, std::sin(a / 2), 0, std::cos(a / 2)}, TINYGLTF_TYPE_VEC4, 4);
  anim.samplers.push_back(s);
  tg::AnimationChannel c;
  c.sampler = 0;
  c.target_node = 1;
  c.target_path = "rotation";
  anim.channels.push_back(c);
  m.animations.push_back(anim);
}

std::string write(const tg::Model& m, const TempDir& dir, const std::string& name) {
  const std::string path = dir.file(name);
  tg::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&m, path, true, true, true, name.ends_with(".glb")));
  return path;
}

// The world transform of animated_model's child: parent translation (x, 0, 0), the parent's
// rest rotation, the child's translation and its rotation about +y.
mat4 child_world(float parent_x, float child_angle_deg) {
  const mat4 parent = glm::rotate(glm::translate(mat4(1.0f), vec3(parent_x, 0, 0)),
                                  glm::radians(90.0f), vec3(0, 0, 1));
  const mat4 child = glm::rotate(glm::translate(mat4(1.0f), vec3(0, 1, 0)),
                                 glm::radians(child_angle_deg), vec3(0, 1, 0));
  return parent * child;
}

void expect_triangle_at(const Scene& scene, const mat4& world) {
  ASSERT_EQ(scene.meshes.size(), 1u);
  for (int i = 0; i < 3; ++i) {
    const vec3 rest(kRestTriangle[3 * i], kRestTriangle[3 * i + 1], kRestTriangle[3 * i + 2]);
    expect_near(scene.meshes[0].positions[size_t(i)], vec3(world * vec4(rest, 1.0f)), 1e-5f);
  }
}

TEST(AnimationLoading, GltfParentTranslationMovesTheChildMeshAndLight) {
  TempDir dir;
  for (const char* name : {"anim.gltf", "anim.glb"}) {
    Scene scene = load_scene(write(animated_model("LINEAR"), dir, name));
    ASSERT_EQ(scene.animation.tracks.size(), 1u);
    EXPECT_EQ(scene.animation.tracks[0].name, "parent");
    ASSERT_EQ(scene.animation.meshes.size(), 1u);
    ASSERT_EQ(scene.animation.lights.size(), 1u);
    EXPECT_FLOAT_EQ(scene.animation.duration(), 2.0f);
    // As loaded: the rest pose (1, 0, 0).
    expect_triangle_at(scene, child_world(1.0f, 0.0f));
    for (float t : {0.0f, 0.5f, 1.0f, 1.75f}) {
      const SceneChange change = animate(scene, t);
      EXPECT_EQ(change.moved_meshes, std::vector<uint32_t>{0});
      EXPECT_TRUE(change.lights);
      const mat4 world = child_world(2.0f * t, 0.0f);
      expect_triangle_at(scene, world);
      expect_near(scene.lights[0].position, vec3(world[3]), 1e-5f);
    }
    // Looping: 2.5 s is 0.5 s.
    animate(scene, 2.5f);
    expect_triangle_at(scene, child_world(1.0f, 0.0f));
  }
}

TEST(AnimationLoading, GltfStepHoldsTheLastKey) {
  TempDir dir;
  Scene scene = load_scene(write(animated_model("STEP"), dir, "step.gltf"));
  EXPECT_TRUE(scene.animation.tracks[0].translation.step);
  animate(scene, 1.5f);
  expect_triangle_at(scene, child_world(0.0f, 0.0f));
  scene.animation.loop = false;
  animate(scene, 5.0f);  // clamped to the end: the last key
  expect_triangle_at(scene, child_world(4.0f, 0.0f));
}

TEST(AnimationLoading, GltfRotationSlerpsAndAnimationsPlayTogether) {
  TempDir dir;
  tg::Model m = animated_model("LINEAR");
  add_child_rotation(m);
  Scene scene = load_scene(write(m, dir, "rot.gltf"));
  ASSERT_EQ(scene.animation.tracks.size(), 2u);
  ASSERT_EQ(scene.animation.meshes.size(), 1u);
  EXPECT_EQ(scene.animation.meshes[0].tracks, (std::vector<uint32_t>{0, 1}));  // outermost first
  // At 1 s the parent is at x = 2 and the child has turned halfway: 60 degrees.
  animate(scene, 1.0f);
  expect_triangle_at(scene, child_world(2.0f, 60.0f));
  animate(scene, 0.5f);
  expect_triangle_at(scene, child_world(1.0f, 30.0f));
}

TEST(AnimationLoading, GltfCubicSplineUsesTheValueKeys) {
  TempDir dir;
  tg::Model m = animated_model("CUBICSPLINE");
  // (in-tangent, value, out-tangent) per key; the tangents are nonsense that must be ignored.
  m.animations[0].samplers[0].output =
      add_floats(m, {9, 9, 9, 0, 0, 0, 9, 9, 9, 9, 9, 9, 4, 0, 0, 9, 9, 9}, TINYGLTF_TYPE_VEC3, 3);
  Scene scene = load_scene(write(m, dir, "cubic.gltf"));
  animate(scene, 1.0f);
  expect_triangle_at(scene, child_world(2.0f, 0.0f));
}

TEST(AnimationLoading, GltfNormalizedShortRotations) {
  TempDir dir;
  tg::Model m = animated_model("LINEAR");
  add_child_rotation(m);
  const float a = glm::radians(120.0f);
  const auto q = [](float x) { return int16_t(std::lround(x * 32767.0f)); };
  const int acc = add_data(
      m, std::vector<int16_t>{0, 0, 0, 32767, 0, q(std::sin(a / 2)), 0, q(std::cos(a / 2))},
      TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, 2);
  m.accessors[size_t(acc)].normalized = true;
  m.animations[1].samplers[0].output = acc;
  Scene scene = load_scene(write(m, dir, "short.gltf"));
  animate(scene, 1.0f);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const mat4 world = child_world(2.0f, 60.0f);
  for (int i = 0; i < 3; ++i) {
    const vec3 rest(kRestTriangle[3 * i], kRestTriangle[3 * i + 1], kRestTriangle[3 * i + 2]);
    expect_near(scene.meshes[0].positions[size_t(i)], vec3(world * vec4(rest, 1.0f)), 1e-3f);
  }
}

TEST(AnimationLoading, GltfErrorsNameTheFile) {
  TempDir dir;
  struct Case {
    const char* name;
    void (*edit)(tg::Model&);
    const char* expected;
  };
  const Case cases[] = {
      {"input.gltf", [](tg::Model& m) { m.animations[0].samplers[0].input = 99; },
       "accessor 99 does not exist"},
      {"output.gltf", [](tg::Model& m) { m.animations[0].samplers[0].output = -1; },
       "accessor -1 does not exist"},
      {"sampler.gltf", [](tg::Model& m) { m.animations[0].channels[0].sampler = 3; },
       "sampler 3 does not exist"},
      {"node.gltf", [](tg::Model& m) { m.animations[0].channels[0].target_node = 7; },
       "target node 7 does not exist"},
      {"count.gltf",
       [](tg::Model& m) {
         m.animations[0].samplers[0].output =
             add_floats(m, {0, 0, 0, 1, 0, 0, 2, 0, 0}, TINYGLTF_TYPE_VEC3, 3);
       },
       "2 key times but 3 output values"},
      {"times.gltf",
       [](tg::Model& m) {
         m.animations[0].samplers[0].input = add_floats(m, {1, 1}, TINYGLTF_TYPE_SCALAR, 1);
       },
       "key times must increase"},
      {"type.gltf",
       [](tg::Model& m) {
         m.animations[0].samplers[0].output = add_floats(m, {0, 0, 0, 1}, TINYGLTF_TYPE_VEC2, 2);
       },
       "expected VEC3"},
      {"range.gltf", [](tg::Model& m) { m.accessors.back().count = 1000; }, "run past the end"},
      {"interp.gltf", [](tg::Model& m) { m.animations[0].samplers[0].interpolation = "SMOOTH"; },
       "unknown interpolation 'SMOOTH'"},
      {"path.gltf", [](tg::Model& m) { m.animations[0].channels[0].target_path = "colour"; },
       "unknown target path 'colour'"},
  };
  for (const Case& c : cases) {
    tg::Model m = animated_model("LINEAR");
    c.edit(m);
    const std::string path = write(m, dir, c.name);
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_TRUE(contains(message, path)) << c.name << ": " << message;
    EXPECT_TRUE(contains(message, c.expected)) << c.name << ": " << message;
  }
}

TEST(AnimationLoading, GltfWeightsChannelsAreIgnored) {
  TempDir dir;
  tg::Model m = animated_model("LINEAR");
  tg::AnimationChannel c = m.animations[0].channels[0];
  c.target_path = "weights";
  m.animations[0].channels.push_back(c);
  Scene scene = load_scene(write(m, dir, "weights.gltf"));
  EXPECT_EQ(scene.animation.tracks.size(), 1u);
}

constexpr const char* kQuadObj = "o quad\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n";

TEST(AnimationLoading, SceneFileModelAnimationKeepsUnkeyedChannelsStatic) {
  TempDir dir;
  dir.write("quad.obj", kQuadObj);
  const std::string path = dir.write("a.bounce.json", R"({
    "models": [{"file": "quad.obj", "translate": [10, 0, 0], "rotate": [0, 30, 0], "scale": 2,
                "animation": {"keys": [{"time": 0, "translate": [10, 0, 0]},
                                       {"time": 2, "translate": [12, 0, 4]}]}},
               {"file": "quad.obj", "translate": [0, 5, 0], "scale": 2,
                "animation": {"interpolation": "step",
                              "keys": [{"time": 0, "rotate": [0, 0, 0]},
                                       {"time": 1, "rotate": [0, 90, 0]},
                                       {"time": 4, "rotate": [0, 180, 0]}]}},
               {"file": "quad.obj", "translate": [0, 9, 0],
                "animation": {"keys": [{"time": 0, "rotate": [0, 0, 0]},
                                       {"time": 2, "rotate": [0, 90, 0]}]}}],
    "loop": false
  })");
  Scene scene = load_scene(path);
  ASSERT_EQ(scene.meshes.size(), 3u);
  EXPECT_FALSE(scene.animation.loop);
  EXPECT_FLOAT_EQ(scene.animation.duration(), 4.0f);
  const vec3 corner(1, 0, 1);
  const auto static_at = [](vec3 t, float ry_deg, float s, vec3 p) {
    return vec3(glm::rotate(glm::translate(mat4(1.0f), t), glm::radians(ry_deg), vec3(0, 1, 0)) *
                vec4(s * p, 1.0f));
  };
  // At rest, as loaded.
  expect_near(scene.meshes[0].positions[2], static_at(vec3(10, 0, 0), 30, 2, corner), 1e-5f);
  animate(scene, 1.0f);
  // Model 0: translation halfway, rotation and scale still the static 30 degrees and 2.
  expect_near(scene.meshes[0].positions[2], static_at(vec3(11, 0, 2), 30, 2, corner), 1e-5f);
  // Model 1 steps: at 1 s it holds the 90 degree key; scale and translation static.
  expect_near(scene.meshes[1].positions[2], static_at(vec3(0, 5, 0), 90, 2, corner), 1e-5f);
  // Model 2 slerps: 45 degrees.
  expect_near(scene.meshes[2].positions[2], static_at(vec3(0, 9, 0), 45, 1, corner), 1e-5f);
  animate(scene, 0.5f);
  expect_near(scene.meshes[1].positions[2], static_at(vec3(0, 5, 0), 0, 2, corner), 1e-5f);
  animate(scene, 3.9f);
  expect_near(scene.meshes[1].positions[2], static_at(vec3(0, 5, 0), 90, 2, corner), 1e-5f);
  animate(scene, 10.0f);  // no loop: the last keys
  expect_near(scene.meshes[0].positions[2], static_at(vec3(12, 0, 4), 30, 2, corner), 1e-5f);
  expect_near(scene.meshes[1].positions[2], static_at(vec3(0, 5, 0), 180, 2, corner), 1e-5f);
}

TEST(AnimationLoading, SceneFileAnimationIsOutermostOverGltfAnimation) {
  TempDir dir;
  const std::string gltf = write(animated_model("LINEAR"), dir, "anim.gltf");
  (void)gltf;
  const std::string path = dir.write("g.bounce.json", R"({
    "models": [{"builtin": "cornell"},
               {"file": "anim.gltf", "rotate": [0, 90, 0],
                "animation": {"keys": [{"time": 0, "translate": [0, 0, 0]},
                                       {"time": 2, "translate": [0, 0, 8]}]}}]
  })");
  Scene scene = load_scene(path);
  const Mesh* tri = find_mesh(scene, "tri");
  ASSERT_NE(tri, nullptr);
  const uint32_t index = uint32_t(tri - scene.meshes.data());
  const AnimatedMesh* am = nullptr;
  for (const auto& a : scene.animation.meshes)
    if (a.mesh == index) am = &a;
  ASSERT_NE(am, nullptr);
  ASSERT_EQ(am->tracks.size(), 2u);
  EXPECT_EQ(scene.animation.tracks[am->tracks[0]].name, "models[1]");
  EXPECT_EQ(scene.animation.tracks[am->tracks[1]].name, "parent");
  ASSERT_EQ(scene.lights.size(), 1u);  // the glTF's point light (the Cornell box has an area light)
  animate(scene, 1.0f);
  const mat4 outer =
      glm::rotate(glm::translate(mat4(1.0f), vec3(0, 0, 4)), glm::radians(90.0f), vec3(0, 1, 0));
  const mat4 world = outer * child_world(2.0f, 0.0f);
  for (int i = 0; i < 3; ++i) {
    const vec3 rest(kRestTriangle[3 * i], kRestTriangle[3 * i + 1], kRestTriangle[3 * i + 2]);
    expect_near(tri->positions[size_t(i)], vec3(world * vec4(rest, 1.0f)), 1e-5f);
  }
  expect_near(scene.lights[0].position, vec3(world[3]), 1e-5f);
  // The Cornell box does not move.
  for (uint32_t k : animate(scene, 1.5f).moved_meshes) EXPECT_EQ(k, index);
}

TEST(AnimationLoading, SceneFileLightKeysAndCameraPath) {
  TempDir dir;
  const std::string path = dir.write("l.bounce.json", R"({
    "models": [{"builtin": "cornell"}],
    "lights": [
      {"type": "sphere", "position": [0, 1, 0], "radius": 0.1, "radiance": 5,
       "animation": {"keys": [{"time": 0, "position": [0, 1, 0]},
                              {"time": 2, "position": [2, 1, 4]}]}},
      {"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "intensity": 1,
       "animation": {"keys": [{"time": 0, "direction": [0, -1, 0]},
                              {"time": 2, "position": [1, 3, 0], "direction": [1, 0, 0]}]}},
      {"type": "point", "position": [5, 5, 5], "intensity": 1}
    ],
    "camera_path": {"keys": [{"time": 0, "position": [0, 0, -1], "look_at": [0, 0, 0]},
                             {"time": 4, "position": [4, 0, -1], "look_at": [0, 2, 0]}]}
  })");
  Scene scene = load_scene(path);
  EXPECT_EQ(scene.animation.lights.size(), 2u);
  EXPECT_FLOAT_EQ(scene.animation.duration(), 4.0f);
  ASSERT_EQ(scene.lights.size(), 3u);  // the Cornell box's light is an area light
  animate(scene, 1.0f);
  expect_near(scene.lights[0].position, vec3(1, 1, 2), 1e-5f);
  // The spot: position keyed only at 2 s (held before), direction turned halfway (45 degrees).
  expect_near(scene.lights[1].position, vec3(1, 3, 0), 1e-5f);
  expect_near(scene.lights[1].direction, glm::normalize(vec3(1, -1, 0)), 1e-5f);
  expect_near(scene.lights[2].position, vec3(5, 5, 5), 0.0f);
  animate(scene, 2.0f);  // the end of a looping 4 s animation, not yet wrapped
  expect_near(scene.lights[0].position, vec3(2, 1, 4), 1e-5f);
  expect_near(scene.lights[1].direction, vec3(1, 0, 0), 1e-5f);

  const CameraPath& cp = scene.animation.camera_path;
  ASSERT_FALSE(cp.empty());
  const Camera c = cp.at(scene.camera, 1.0f);
  expect_near(c.position, vec3(1, 0, -1), 1e-6f);
  expect_near(c.look_at, vec3(0, 0.5f, 0), 1e-6f);
  EXPECT_EQ(c.vfov_deg, scene.camera.vfov_deg);
  expect_near(cp.at(scene.camera, 9.0f).position, vec3(4, 0, -1), 0.0f);
}

TEST(AnimationLoading, SceneFileErrorsNameFileAndPlace) {
  TempDir dir;
  dir.write("quad.obj", kQuadObj);
  struct Case {
    const char* json;
    const char* expected;
  };
  const Case cases[] = {
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": [{"time": 0, "translate": [0, 0, 0]},
          {"time": 1, "rotation": [0, 0, 0]}]}}]})",
       "models[0].animation.keys[1]: unknown key 'rotation'"},
      {R"({"models": [{"file": "quad.obj"}, {"file": "quad.obj", "animation": {"keys": [
          {"time": 1, "translate": [0, 0, 0]}, {"time": 1, "translate": [1, 0, 0]}]}}]})",
       "models[1].animation.keys[1]: 'time' must be greater"},
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": []}}]})",
       "models[0].animation: 'keys' needs at least one key"},
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": [{"time": 0}]}}]})",
       "models[0].animation.keys[0]: a key needs at least one of"},
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": [{"translate": [0, 0, 0]}]}}]})",
       "models[0].animation.keys[0]: missing required key 'time'"},
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": [{"time": -1, "scale": 2}]}}]})",
       "'time' must not be negative"},
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": [{"time": 0, "scale": -1}]}}]})",
       "'scale' must mirror exactly when"},
      {R"({"models": [{"file": "quad.obj", "animation": {"keys": [{"time": 0, "scale": 1}],
          "interpolation": "cubic"}}]})",
       "'interpolation' must be"},
      {R"({"models": [{"file": "quad.obj", "animation": {"frames": []}}]})",
       "models[0].animation: unknown key 'frames'"},
      {R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1,
          "animation": {"keys": [{"time": 0, "direction": [0, 1, 0]}]}}]})",
       "lights[0].animation.keys[0]: unknown key 'direction'"},
      {R"({"lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": 1,
          "animation": {"keys": [{"time": 0, "position": [0, 1, 0]}]}}]})",
       "lights[0].animation.keys[0]: unknown key 'position'"},
      {R"({"lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0],
          "intensity": 1, "animation": {"keys": [{"time": 0, "direction": [0, 0, 0]}]}}]})",
       "lights[0].animation.keys[0]: 'direction' must not be zero"},
      {R"({"models": [{"file": "quad.obj"}], "camera_path": {"keys": [
          {"time": 0, "position": [0, 0, 0], "look_at": [0, 0, 1]},
          {"time": 2, "position": [0, 0, 0]}]}})",
       "camera_path.keys[1]: missing required key 'look_at'"},
      {R"({"models": [{"file": "quad.obj"}], "camera_path": {"keys": [
          {"time": 0, "position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 1, 0]}]}})",
       "camera_path.keys[0]: unknown key 'up'"},
      {R"({"models": [{"file": "quad.obj"}], "loop": 1})", "'loop' must be true or false"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("e.bounce.json", c.json);
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_TRUE(contains(message, path)) << message;
    EXPECT_TRUE(contains(message, c.expected)) << c.json << "\n-> " << message;
  }
}

// A unit cube centred on the origin, 12 outward-facing triangles.
constexpr const char* kCubeObj =
    "o cube\n"
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 5 8\nf 1 8 4\n"
    "f 2 3 7\nf 2 7 6\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\n";

TEST(AnimationLoading, TracerUpdateAfterAnimateMatchesAFreshBuild) {
  TempDir dir;
  dir.write("cube.obj", kCubeObj);
  // The cube moves in the free floor space at the front, beside the two blocks.
  const std::string path = dir.write("c.bounce.json", R"({
    "models": [{"builtin": "cornell"},
               {"file": "cube.obj", "translate": [0.36, 0.05, 0.14], "scale": 0.1,
                "animation": {"keys": [
                  {"time": 0, "translate": [0.36, 0.05, 0.14], "rotate": [0, 0, 0]},
                  {"time": 2, "translate": [0.48, 0.05, 0.06], "rotate": [0, 80, 0]}]}}]
  })");
  Scene scene = load_scene(path);
  const Mesh* cube = find_mesh(scene, "cube");
  ASSERT_NE(cube, nullptr);
  const uint32_t cube_index = uint32_t(cube - scene.meshes.data());
  auto tracer = make_embree_tracer(scene);
  const auto stale = make_embree_tracer(scene);  // never updated: shows that the update matters
  for (float t : {0.7f, 1.3f}) {
    const SceneChange change = animate(scene, t);
    ASSERT_EQ(change.moved_meshes, std::vector<uint32_t>{cube_index});
    tracer->update(scene, change.moved_meshes);
    const auto fresh = make_embree_tracer(scene);
    // The cube's centre now: rays from around the box towards it and slightly beside it.
    vec3 centre(0.0f);
    for (const vec3& p : cube->positions) centre += p / float(cube->positions.size());
    int cube_hits = 0, stale_differs = 0;
    for (const vec3& origin : {vec3(0.278f, 0.5f, -0.5f), vec3(0.5f, 0.45f, -0.2f),
                               vec3(0.53f, 0.3f, 0.05f), vec3(0.4f, 0.5f, 0.1f)}) {
      for (const vec3& offset : {vec3(0.0f), vec3(0.02f, 0.0f, 0.0f), vec3(0.0f, 0.03f, 0.0f),
                                 vec3(-0.03f, 0.0f, 0.02f), vec3(0.0f, 0.0f, 0.1f)}) {
        Ray ray;
        ray.origin = origin;
        ray.direction = glm::normalize(centre + offset - origin);
        const Hit a = tracer->intersect(ray);
        const Hit b = fresh->intersect(ray);
        ASSERT_TRUE(b.valid());
        EXPECT_EQ(a.mesh, b.mesh);
        EXPECT_EQ(a.triangle, b.triangle);
        EXPECT_NEAR(a.t, b.t, 1e-5f);
        cube_hits += b.mesh == cube_index;
        const Hit c = stale->intersect(ray);
        stale_differs += c.mesh != b.mesh || std::abs(c.t - b.t) > 1e-4f;
      }
    }
    EXPECT_GE(cube_hits, 12);  // the rays do go through the moved cube
    EXPECT_GE(stale_differs, 4);
  }
}

}  // namespace
}  // namespace bounce
