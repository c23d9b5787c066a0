// Real Quake 3 levels: Debian's OpenArena maps (scripts/setup.sh installs them). Skipped, with a
// message, where they are not installed.
#include <cstring>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "bounce/scene/quake/bsp.h"
#include "bounce/scene/quake/load_quake.h"
#include "bounce/scene/quake/pk3.h"
#include "scene_test_util.h"

namespace bounce::scene_test {
namespace {

const std::string kBase = "/usr/share/games/openarena/baseoa/";
const std::string kMaps = kBase + "pak1-maps.pk3";

#define SKIP_WITHOUT_OPENARENA()                                                   \
  if (!std::filesystem::exists(kMaps))                                             \
  GTEST_SKIP() << kMaps                                                            \
               << " is missing: install openarena-081-maps (scripts/setup.sh) to " \
                  "test on real levels"

int32_t lump_length(const std::vector<uint8_t>& b, int lump) {
  int32_t v;
  std::memcpy(&v, b.data() + 12 + 8 * lump, 4);
  return v;
}

TEST(OpenArenaMaps, CountsEqualLumpSizesOverRecordSizes) {
  SKIP_WITHOUT_OPENARENA();
  const quake::Pk3Archive maps(kMaps);
  for (const char* name : {"maps/oa_dm1.bsp", "maps/aggressor.bsp", "maps/oa_ctf2.bsp"}) {
    const std::vector<uint8_t> bytes = maps.read(name);
    const quake::BspFile bsp = quake::parse_bsp(bytes, name);
    EXPECT_EQ(bsp.faces.size() * quake::kFaceBytes, size_t(lump_length(bytes, quake::kLumpFaces)));
    EXPECT_EQ(bsp.vertices.size() * quake::kVertexBytes,
              size_t(lump_length(bytes, quake::kLumpVertices)));
    EXPECT_EQ(bsp.mesh_vertices.size() * 4, size_t(lump_length(bytes, quake::kLumpMeshVertices)));
    EXPECT_EQ(bsp.textures.size() * quake::kTextureBytes,
              size_t(lump_length(bytes, quake::kLumpTextures)));
    EXPECT_GT(bsp.faces.size(), 500u) << name;
    EXPECT_GT(bsp.vertices.size(), 2000u) << name;
    ASSERT_FALSE(bsp.models.empty());
    // The world model's box (Quake units, made from its brushes) holds every brush face.
    const quake::BspModel& world = bsp.models[0];
    for (int i = 0; i < world.face_count; ++i) {
      const quake::BspFace& f = bsp.faces[size_t(world.first_face + i)];
      if (f.type != 1) continue;  // patch control points and models may stick out
      for (int v = 0; v < f.vertex_count; ++v) {
        const auto& p = bsp.vertices[size_t(f.first_vertex + v)].position;
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(p[size_t(a)], world.mins[size_t(a)] - 16.0f);
          EXPECT_LE(p[size_t(a)], world.maxs[size_t(a)] + 16.0f);
        }
      }
    }
  }
}

TEST(OpenArenaMaps, LevelLoadsWithSaneBoundsCameraAndFrontFaces) {
  SKIP_WITHOUT_OPENARENA();
  testing::internal::CaptureStderr();
  quake::QuakeMap map = quake::load_quake_map(kMaps + ":maps/kaos.bsp");
  testing::internal::GetCapturedStderr();
  Scene& scene = map.scene;
  scene.finalize();
  const quake::QuakeStats& s = map.stats;
  EXPECT_EQ(s.triangles, scene.triangle_count());
  EXPECT_GT(s.faces_by_type[1], 0u);
  EXPECT_GT(s.faces_by_type[2], 0u);
  EXPECT_GT(s.patches, 0u);
  EXPECT_GT(s.spawn_points, 0u);
  EXPECT_EQ(s.point_lights + s.spot_lights, 30u);  // kaos keeps its light entities
  // A level a few tens of metres across, with the spawn camera inside it.
  const Bounds& b = scene.bounds;
  EXPECT_GT(b.diagonal(), 10.0f);
  EXPECT_LT(b.diagonal(), 500.0f);
  for (int a = 0; a < 3; ++a) {
    EXPECT_GT(scene.camera.position[a], b.lo[a]);
    EXPECT_LT(scene.camera.position[a], b.hi[a]);
  }
  // Our front faces are the map's: the winding's normal agrees with the vertex normals the
  // level compiler wrote, for flat faces and for tessellated patches alike.
  size_t agree = 0, total = 0;
  for (const Mesh& m : scene.meshes)
    for (uint32_t t = 0; t < m.triangle_count(); ++t) {
      const vec3 g = m.face_normal_area2(t);
      if (glm::length(g) < 1e-8f) continue;
      const uvec3 i = m.triangles[t];
      const vec3 n = m.normals[i.x] + m.normals[i.y] + m.normals[i.z];
      agree += glm::dot(g, n) > 0.0f;
      ++total;
    }
  EXPECT_GT(double(agree), 0.99 * double(total)) << agree << " of " << total;
}

TEST(OpenArenaMaps, TexturesAndLightsComeFromTheArchives) {
  SKIP_WITHOUT_OPENARENA();
  if (!std::filesystem::exists(kBase + "pak4-textures.pk3"))
    GTEST_SKIP() << "openarena-081-textures is not installed";
  testing::internal::CaptureStderr();
  const quake::QuakeMap map = quake::load_quake_map(kMaps + ":maps/aggressor.bsp");
  testing::internal::GetCapturedStderr();
  EXPECT_GT(map.stats.textures, 10u);
  EXPECT_LT(map.stats.textures_missing, map.stats.textures);
  EXPECT_GE(map.stats.archives, 2u);
  // aggressor keeps its 84 light entities.
  EXPECT_EQ(map.stats.point_lights + map.stats.spot_lights, 84u);
  size_t textured = 0;
  for (const Material& m : map.scene.materials) textured += m.albedo_texture >= 0;
  EXPECT_EQ(textured, map.stats.textures);
  for (const Texture& t : map.scene.textures) {
    EXPECT_LE(t.width, 256);
    EXPECT_LE(t.height, 256);
  }
}

// Random byte flips and truncations of a real map, parsed from memory: every case either loads
// or throws bounce::Error; none may crash (also meant for the asan preset).
TEST(OpenArenaMaps, FuzzedMapsLoadOrFailCleanly) {
  SKIP_WITHOUT_OPENARENA();
  const std::vector<uint8_t> original = quake::Pk3Archive(kMaps).read("maps/oa_ctf2.bsp");
  quake::QuakeOptions options;
  options.patch_level = 2;
  std::mt19937 rng(2024);
  std::vector<uint8_t> bytes;
  int loaded = 0, rejected = 0;
  const int cases = 3000;
  testing::internal::CaptureStderr();  // every case warns that its textures are missing
  for (int c = 0; c < cases; ++c) {
    bytes = original;
    if (c % 3 == 2) {
      bytes.resize(std::uniform_int_distribution<size_t>(0, original.size() - 1)(rng));
    } else {
      // Half the flips land in the header, entities and texture names, where one byte matters
      // most; the rest anywhere.
      const size_t head = std::min<size_t>(4096, bytes.size());
      const int flips = std::uniform_int_distribution<int>(1, 8)(rng);
      for (int f = 0; f < flips; ++f) {
        const size_t span = (f % 2 == 0) ? head : bytes.size();
        const size_t at = std::uniform_int_distribution<size_t>(0, span - 1)(rng);
        bytes[at] ^= uint8_t(1u << std::uniform_int_distribution<int>(0, 7)(rng));
      }
    }
    try {
      quake::QuakeMap map = quake::load_quake_bsp(bytes, "fuzz.bsp", options, /*archives=*/nullptr);
      map.scene.finalize();
      ++loaded;
    } catch (const Error&) {
      ++rejected;
    }
  }
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(loaded + rejected, cases);
  EXPECT_GT(loaded, 0);
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace bounce::scene_test
