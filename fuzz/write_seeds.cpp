// Writes the small seed inputs of the Quake fuzz targets: a level with a floor, a Bezier patch and
// a light (every face type the loader tessellates, and entities), bare and inside a .pk3 with a
// shader script. Real OpenArena maps are seeds too (scripts/fuzz.sh), but at 0.7 MB and more each
// run of them is slow; these few hundred bytes let the fuzzer mutate every lump quickly.
#include <cstdio>
#include <string>

#include "scene/bsp_build.h"

namespace {

void write(const std::string& path, const std::string& bytes) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) {
    std::fprintf(stderr, "write_seeds: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: write_seeds BSP_DIR PK3_DIR\n");
    return 2;
  }
  using bounce::scene_test::BspBuild;
  BspBuild b = BspBuild::floor();
  b.entities +=
      "{\n\"classname\" \"light\"\n\"origin\" \"64 64 96\"\n\"light\" \"300\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"16 16 32\"\n\"angle\" \"45\"\n}\n";
  // A 3 x 3 patch arching over the floor.
  BspBuild::Face patch;
  patch.type = 2;
  patch.first_vertex = int32_t(b.vertices.size());
  patch.vertex_count = 9;
  patch.size = {3, 3};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      b.vertices.push_back(
          {{32.0f * float(i) + 32.0f, 32.0f * float(j) + 32.0f, (i == 1 && j == 1) ? 48.0f : 16.0f},
           {0, 0, 1},
           {float(i) / 2.0f, float(j) / 2.0f}});
  b.faces.push_back(patch);
  const std::string bsp = b.bytes();
  write(std::string(argv[1]) + "/room.bsp", bsp);
  write(std::string(argv[2]) + "/room.pk3",
        bounce::scene_test::stored_zip(
            {{"maps/room.bsp", bsp},
             {"scripts/test.shader",
              "textures/test/floor\n{\n\tq3map_surfacelight 100\n\t{\n\t\tmap "
              "textures/test/floor.tga\n\t}\n}\n"}}));
  return 0;
}
