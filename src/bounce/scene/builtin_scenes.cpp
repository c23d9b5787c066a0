// Built-in scenes: the measured Cornell box, a scalable room of cubes and a light-leak test.
#include <algorithm>
#include <cmath>

#include "bounce/core/error.h"
#include "bounce/core/rng.h"
#include "bounce/scene/builtin_data.h"
#include "bounce/scene/load.h"

namespace bounce {

namespace {

Material diffuse(const char* name, vec3 albedo) {
  Material m;
  m.name = name;
  m.albedo = albedo;
  return m;
}

Material emitter(const char* name, vec3 radiance) {
  Material m;
  m.name = name;
  m.albedo = vec3(0.0f);
  m.emission = radiance;
  return m;
}

// Appends a quad as triangles (0,1,2), (0,2,3); it faces where cross(p1 - p0, p2 - p0) points.
void add_quad(Mesh& mesh, vec3 p0, vec3 p1, vec3 p2, vec3 p3, uint32_t material) {
  const uint32_t base = uint32_t(mesh.positions.size());
  for (const vec3& p : {p0, p1, p2, p3}) mesh.positions.push_back(p);
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  mesh.materials.insert(mesh.materials.end(), 2, material);
}

// The six faces of a box over corners 0..7, corner i having x = bit 0, y = bit 1, z = bit 2;
// each quad winds so that its normal points out of the box.
constexpr uint32_t kBoxFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

// Appends a box (8 shared corners, 12 triangles) given its corners in the order above. `inward`
// turns the faces inside, for rooms.
void add_box_corners(Mesh& mesh, const vec3 (&corners)[8], uint32_t material, bool inward) {
  const uint32_t base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), std::begin(corners), std::end(corners));
  for (const auto& f : kBoxFaces) {
    uvec3 a(base + f[0], base + f[1], base + f[2]);
    uvec3 b(base + f[0], base + f[2], base + f[3]);
    if (inward) {
      std::swap(a.y, a.z);
      std::swap(b.y, b.z);
    }
    mesh.triangles.push_back(a);
    mesh.triangles.push_back(b);
  }
  mesh.materials.insert(mesh.materials.end(), 12, material);
}

void add_box(Mesh& mesh, vec3 lo, vec3 hi, uint32_t material, bool inward) {
  vec3 corners[8];
  for (int i = 0; i < 8; ++i)
    corners[i] = vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  add_box_corners(mesh, corners, material, inward);
}

// A cube of edge `edge` centred at `centre`, turned by `angle` radians about the y axis.
void add_cube(Mesh& mesh, vec3 centre, float edge, float angle, uint32_t material) {
  const float c = std::cos(angle), s = std::sin(angle), h = 0.5f * edge;
  vec3 corners[8];
  for (int i = 0; i < 8; ++i) {
    const float x = i & 1 ? h : -h, y = i & 2 ? h : -h, z = i & 4 ? h : -h;
    // A rotation keeps the handedness, so the faces still wind outwards.
    corners[i] = centre + vec3(c * x + s * z, y, -s * x + c * z);
  }
  add_box_corners(mesh, corners, material, false);
}

Mesh make_mesh(const char* name) {
  Mesh m;
  m.name = name;
  return m;
}

// Sets the scene's camera (up is +y in every built-in scene).
void place_camera(Scene& scene, vec3 position, vec3 look_at, float vfov_deg) {
  scene.camera = Camera{position, look_at, vec3(0.0f, 1.0f, 0.0f), vfov_deg};
  scene.has_camera = true;
}

}  // namespace

// The measured Cornell box of scenes/cornell-box (see DESIGN.md): 16 quads = 32 triangles, the
// ceiling light an emissive quad facing down, seen from the standard camera.
Scene make_cornell() {
  Scene scene = load_obj_text(builtin_data::kCornellObj, builtin_data::kCornellMtl, "cornell");
  scene.source = "cornell";
  place_camera(scene, vec3(0.278f, 0.273f, -0.800f), vec3(0.278f, 0.273f, 0.0f), 39.3077f);
  scene.finalize();
  return scene;
}

// A scalable stress scene: a closed 10 x 6 x 10 m room (x and z in [-5, 5], y in [0, 6]; 12
// triangles, "room"), a 1.5 x 1.5 m emissive quad 1 cm under the ceiling facing down (2
// triangles, "light", radiance 20 W/(sr m^2), about 141 W) and `cube_count` cubes (12 triangles
// each, one mesh "cubes"), so 14 + 12 * cube_count triangles in all. The cubes are scattered
// with Pcg32(seed) through the room, clear of the walls, of the light and of the 1.5 m strip
// along the -z wall where the camera stands; each is turned about y by a random angle and given
// a colour from a small palette. Their edges shrink as room / cbrt(count) so that the volume
// they fill stays about the same; they may overlap (placing them is O(count)). The camera stands
// near the -z wall looking into the room.
Scene make_cubes(uint32_t cube_count, uint32_t seed) {
  if (cube_count == 0) fail("cubes: the cube count must be positive");
  Scene scene;
  scene.source = fmt::format("cubes:{}:{}", cube_count, seed);
  scene.materials = {
      diffuse("wall", vec3(0.75f, 0.75f, 0.72f)), emitter("light", vec3(20.0f)),
      diffuse("white", vec3(0.8f, 0.8f, 0.78f)),  diffuse("red", vec3(0.7f, 0.15f, 0.12f)),
      diffuse("green", vec3(0.2f, 0.6f, 0.2f)),   diffuse("blue", vec3(0.15f, 0.3f, 0.7f)),
      diffuse("yellow", vec3(0.75f, 0.65f, 0.2f))};
  constexpr uint32_t kFirstPaletteMaterial = 2, kPaletteSize = 5;

  Mesh room = make_mesh("room");
  add_box(room, vec3(-5.0f, 0.0f, -5.0f), vec3(5.0f, 6.0f, 5.0f), 0, /*inward=*/true);
  Mesh light = make_mesh("light");
  const float y = 5.99f, h = 0.75f;
  add_quad(light, vec3(-h, y, -h), vec3(h, y, -h), vec3(h, y, h), vec3(-h, y, h), 1);

  // The region cube centres may fill, kept clear of the walls, the light and the camera.
  const vec3 lo(-4.5f, 0.0f, -3.5f), hi(4.5f, 4.8f, 4.5f);
  const vec3 extent = hi - lo;
  const float cell = std::cbrt(extent.x * extent.y * extent.z / float(cube_count));
  const float max_edge = std::min(1.5f, 0.5f * cell);
  Mesh cubes = make_mesh("cubes");
  cubes.positions.reserve(size_t(cube_count) * 8);
  cubes.triangles.reserve(size_t(cube_count) * 12);
  cubes.materials.reserve(size_t(cube_count) * 12);
  Pcg32 rng(seed);
  for (uint32_t i = 0; i < cube_count; ++i) {
    const float edge = max_edge * (0.6f + 0.4f * rng.next_float());
    const float angle = 0.5f * kPi * rng.next_float();
    const float half_xz = 0.7072f * edge;  // half the diagonal: room for any turn
    const float half_y = 0.5f * edge;
    const vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
    const vec3 centre(lo.x + half_xz + u.x * (extent.x - 2.0f * half_xz),
                      lo.y + half_y + u.y * (extent.y - 2.0f * half_y),
                      lo.z + half_xz + u.z * (extent.z - 2.0f * half_xz));
    const uint32_t material = kFirstPaletteMaterial + rng.next_below(kPaletteSize);
    add_cube(cubes, centre, edge, angle, material);
  }

  scene.meshes.push_back(std::move(room));
  scene.meshes.push_back(std::move(light));
  scene.meshes.push_back(std::move(cubes));
  place_camera(scene, vec3(0.0f, 3.0f, -4.8f), vec3(0.0f, 2.0f, 0.0f), 60.0f);
  scene.finalize();
  return scene;
}

// The light-leak test: a closed 4 x 2.5 x 4 m room (x, z in [0, 4], y in [0, 2.5]; "room") split
// at x = 2 by a 2 cm thick wall (a closed box over x in [1.99, 2.01] that meets the floor, the
// ceiling and the z = 0 and z = 4 walls exactly, so no light can pass; "wall"). A sphere light
// (radius 0.1 m, radiance 50 W/(sr m^2), about 20 W) hangs in the x < 2 half only, so any light
// that a technique puts on the far side of the wall, or any darkening it pulls through the wall
// onto the lit side, is a leak. The camera stands in the lit half looking diagonally at the wall.
Scene make_leak() {
  Scene scene;
  scene.source = "leak";
  scene.materials = {diffuse("white", vec3(0.75f, 0.75f, 0.72f))};
  Mesh room = make_mesh("room");
  add_box(room, vec3(0.0f), vec3(4.0f, 2.5f, 4.0f), 0, /*inward=*/true);
  Mesh wall = make_mesh("wall");
  add_box(wall, vec3(1.99f, 0.0f, 0.0f), vec3(2.01f, 2.5f, 4.0f), 0, /*inward=*/false);
  scene.meshes.push_back(std::move(room));
  scene.meshes.push_back(std::move(wall));
  Light light = Light::sphere(vec3(1.0f, 1.5f, 2.0f), 0.1f, vec3(50.0f));
  light.name = "light";
  scene.lights.push_back(light);
  place_camera(scene, vec3(0.3f, 1.6f, 0.3f), vec3(2.0f, 0.8f, 2.6f), 60.0f);
  scene.finalize();
  return scene;
}

}  // namespace bounce
