#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "bounce/scene/load.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

using scene_test::error_of;
using scene_test::expect_near;
using scene_test::find_mesh;

// Every undirected edge of a closed mesh is shared by exactly two triangles that traverse it in
// opposite directions (consistent winding).
void expect_closed(const Mesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const uvec3& t : mesh.triangles) {
    const uint32_t v[3] = {t.x, t.y, t.z};
    for (int i = 0; i < 3; ++i) ++directed[{v[i], v[(i + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << mesh.name << ": edge used twice in one direction";
    const auto opposite = directed.find({edge.second, edge.first});
    EXPECT_TRUE(opposite != directed.end() && opposite->second == 1)
        << mesh.name << ": open edge " << edge.first << "-" << edge.second;
  }
}

TEST(BuiltinScenes, CornellCountsAndLight) {
  const Scene scene = make_cornell();
  EXPECT_EQ(scene.source, "cornell");
  EXPECT_EQ(scene.meshes.size(), 16u);
  EXPECT_EQ(scene.triangle_count(), 32u);  // 16 quads in the OBJ
  ASSERT_EQ(scene.area_lights.size(), 1u);
  const AreaLight& light = scene.area_lights[0];
  EXPECT_NEAR(light.area, 0.130f * 0.105f, 1e-6f);
  expect_near(light.radiance, vec3(17.0f, 12.0f, 4.0f), 0.0f);
  EXPECT_EQ(light.triangles.size(), 2u);
  // The light quad faces down and reflects nothing.
  const Mesh* quad = find_mesh(scene, "light");
  ASSERT_NE(quad, nullptr);
  for (uint32_t t = 0; t < quad->triangle_count(); ++t) {
    EXPECT_LT(quad->face_normal_area2(t).y, 0.0f);
    expect_near(scene.materials[quad->materials[t]].albedo, vec3(0.0f), 0.0f);
  }
  EXPECT_TRUE(scene.lights.empty());
}

TEST(BuiltinScenes, CornellMaterialsAndBounds) {
  const Scene scene = make_cornell();
  const Mesh* left = find_mesh(scene, "left");
  const Mesh* right = find_mesh(scene, "right");
  ASSERT_NE(left, nullptr);
  ASSERT_NE(right, nullptr);
  const Material& red = scene.materials[left->materials[0]];
  EXPECT_EQ(red.name, "red");
  expect_near(red.albedo, vec3(0.63f, 0.065f, 0.05f), 1e-6f);
  EXPECT_FALSE(red.has_specular());
  expect_near(scene.materials[right->materials[0]].albedo, vec3(0.14f, 0.45f, 0.091f), 1e-6f);
  expect_near(scene.bounds.lo, vec3(0.0f), 1e-6f);
  expect_near(scene.bounds.hi, vec3(0.556f, 0.5488f, 0.5592f), 1e-6f);
  EXPECT_TRUE(scene.has_camera);
  expect_near(scene.camera.position, vec3(0.278f, 0.273f, -0.8f), 1e-6f);
  expect_near(glm::normalize(scene.camera.look_at - scene.camera.position), vec3(0, 0, 1), 1e-6f);
  expect_near(scene.camera.up, vec3(0, 1, 0), 0.0f);
  EXPECT_FLOAT_EQ(scene.camera.vfov_deg, 39.3077f);
}

TEST(BuiltinScenes, CornellQuadsSplitZeroOneTwoZeroTwoThree) {
  const Scene scene = make_cornell();
  const Mesh* left = find_mesh(scene, "left");
  ASSERT_NE(left, nullptr);
  // The OBJ's vertices 17..20 in face order; the red wall's quad is slightly non-planar, so the
  // split decides the geometry.
  ASSERT_EQ(left->positions.size(), 4u);
  expect_near(left->positions[0], vec3(0.5528f, 0.0f, 0.0f), 0.0f);
  expect_near(left->positions[1], vec3(0.5496f, 0.0f, 0.5592f), 0.0f);
  expect_near(left->positions[2], vec3(0.5560f, 0.5488f, 0.5592f), 0.0f);
  expect_near(left->positions[3], vec3(0.5560f, 0.5488f, 0.0f), 0.0f);
  ASSERT_EQ(left->triangles.size(), 2u);
  EXPECT_EQ(left->triangles[0], uvec3(0, 1, 2));
  EXPECT_EQ(left->triangles[1], uvec3(0, 2, 3));
  EXPECT_TRUE(left->normals.empty());
  EXPECT_TRUE(left->uvs.empty());
}

TEST(BuiltinScenes, CubesTriangleCounts) {
  // 12 for the room, 2 for the light quad, 12 per cube.
  EXPECT_EQ(make_cubes(1).triangle_count(), 14u + 12u);
  EXPECT_EQ(make_cubes(37).triangle_count(), 14u + 12u * 37u);
  EXPECT_EQ(make_cubes(10000).triangle_count(), 14u + 120000u);
}

TEST(BuiltinScenes, CubesAreDeterministicPerSeed) {
  const Scene a = make_cubes(200, 7), b = make_cubes(200, 7), c = make_cubes(200, 8);
  const Mesh* ca = find_mesh(a, "cubes");
  const Mesh* cb = find_mesh(b, "cubes");
  const Mesh* cc = find_mesh(c, "cubes");
  ASSERT_TRUE(ca && cb && cc);
  EXPECT_EQ(ca->positions, cb->positions);
  EXPECT_EQ(ca->materials, cb->materials);
  EXPECT_NE(ca->positions, cc->positions);
}

TEST(BuiltinScenes, CubesFitInsideTheRoomAndFaceOut) {
  for (uint32_t n : {1u, 10u, 5000u}) {
    const Scene scene = make_cubes(n, 3);
    EXPECT_GE(scene.bounds.lo.x, -5.0f);
    EXPECT_GE(scene.bounds.lo.y, 0.0f);
    EXPECT_GE(scene.bounds.lo.z, -5.0f);
    EXPECT_LE(scene.bounds.hi.x, 5.0f);
    EXPECT_LE(scene.bounds.hi.y, 6.0f);
    EXPECT_LE(scene.bounds.hi.z, 5.0f);
    const Mesh* cubes = find_mesh(scene, "cubes");
    ASSERT_NE(cubes, nullptr);
    ASSERT_EQ(cubes->positions.size(), 8u * n);
    for (uint32_t c = 0; c < n; ++c) {
      vec3 centre(0.0f);
      for (int k = 0; k < 8; ++k) centre += cubes->positions[8 * c + k] / 8.0f;
      EXPECT_LT(centre.y + 0.5f * glm::length(cubes->positions[8 * c] - centre), 5.99f);
      for (uint32_t t = 12 * c; t < 12 * c + 12; ++t) {
        const uvec3 tri = cubes->triangles[t];
        const vec3 mid =
            (cubes->positions[tri.x] + cubes->positions[tri.y] + cubes->positions[tri.z]) / 3.0f;
        EXPECT_GT(glm::dot(cubes->face_normal_area2(t), mid - centre), 0.0f);
      }
    }
    expect_closed(*find_mesh(scene, "room"));
  }
}

TEST(BuiltinScenes, CubesLightAndCamera) {
  const Scene scene = make_cubes(100);
  ASSERT_EQ(scene.area_lights.size(), 1u);
  EXPECT_NEAR(scene.area_lights[0].area, 1.5f * 1.5f, 1e-5f);
  expect_near(scene.area_lights[0].radiance, vec3(20.0f), 0.0f);
  const Mesh* light = find_mesh(scene, "light");
  ASSERT_NE(light, nullptr);
  for (uint32_t t = 0; t < light->triangle_count(); ++t)
    EXPECT_LT(light->face_normal_area2(t).y, 0.0f);
  // The camera is inside the room, and no cube centre lies within 1 m of it.
  const vec3 eye = scene.camera.position;
  EXPECT_TRUE(glm::all(glm::greaterThan(eye, vec3(-5, 0, -5))) &&
              glm::all(glm::lessThan(eye, vec3(5, 6, 5))));
  const Mesh* cubes = find_mesh(scene, "cubes");
  for (const vec3& p : cubes->positions) EXPECT_GT(glm::length(p - eye), 1.0f);
}

TEST(BuiltinScenes, LeakWallSplitsTheRoomAndTheLightIsOnOneSide) {
  const Scene scene = make_leak();
  const Mesh* room = find_mesh(scene, "room");
  const Mesh* wall = find_mesh(scene, "wall");
  ASSERT_TRUE(room && wall);
  EXPECT_EQ(room->triangle_count(), 12u);
  EXPECT_EQ(wall->triangle_count(), 12u);
  expect_closed(*room);
  expect_closed(*wall);
  Bounds wb;
  for (const vec3& p : wall->positions) wb.extend(p);
  expect_near(wb.lo, vec3(1.99f, 0.0f, 0.0f), 0.0f);  // meets floor and the z = 0 wall exactly
  expect_near(wb.hi, vec3(2.01f, 2.5f, 4.0f), 0.0f);  // and the ceiling and the z = 4 wall
  expect_near(scene.bounds.lo, vec3(0.0f), 0.0f);
  expect_near(scene.bounds.hi, vec3(4.0f, 2.5f, 4.0f), 0.0f);
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::kSphere);
  EXPECT_FLOAT_EQ(light.radius, 0.1f);
  EXPECT_LT(light.position.x + light.radius, 1.99f);
  EXPECT_TRUE(scene.area_lights.empty());
  EXPECT_LT(scene.camera.position.x, 1.99f);
  EXPECT_GT(scene.camera.look_at.x, scene.camera.position.x);
  for (const Material& m : scene.materials) EXPECT_GE(m.albedo.x, 0.7f);
}

TEST(LoadScene, BuiltinSpecs) {
  EXPECT_EQ(load_scene("cornell").triangle_count(), 32u);
  EXPECT_EQ(load_scene("leak").source, "leak");
  EXPECT_EQ(load_scene("cubes:3").triangle_count(), 14u + 36u);
  const Scene a = load_scene("cubes:3:9"), b = load_scene("cubes:3");
  EXPECT_EQ(a.source, "cubes:3:9");
  EXPECT_NE(find_mesh(a, "cubes")->positions, find_mesh(b, "cubes")->positions);
  EXPECT_EQ(find_mesh(b, "cubes")->positions, find_mesh(make_cubes(3, 1), "cubes")->positions);
}

TEST(LoadScene, RejectsMalformedCubeSpecs) {
  for (const char* spec :
       {"cubes", "cubes:", "cubes:-3", "cubes:abc", "cubes:0", "cubes:3x", "cubes: 3",
        "cubes:3:", "cubes:3:-1", "cubes:3:x", "cubes:99999999999"}) {
    const std::string message = error_of([&] { load_scene(spec); });
    EXPECT_TRUE(scene_test::contains(message, "cubes")) << spec << ": " << message;
  }
}

TEST(LoadScene, RejectsUnknownFilesWithTheAcceptedForms) {
  std::string message = error_of([] { load_scene("scene.fbx"); });
  EXPECT_TRUE(scene_test::contains(message, "scene.fbx")) << message;
  EXPECT_TRUE(scene_test::contains(message, ".gltf")) << message;
  EXPECT_TRUE(scene_test::contains(message, "cubes:N")) << message;
  message = error_of([] { load_scene("/nonexistent/room.obj"); });
  EXPECT_TRUE(scene_test::contains(message, "/nonexistent/room.obj")) << message;
  EXPECT_TRUE(scene_test::contains(message, "no such file")) << message;
  message = error_of([] { load_scene(""); });
  EXPECT_TRUE(scene_test::contains(message, "cornell")) << message;
}

}  // namespace
}  // namespace bounce
