// The environment light through the command line: a model without lights renders lit, with a
// warning; a scene file's sky map renders; a broken map is a clear error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/cli_test_util.h"
#include "bounce/core/image_io.h"
#include "scene/environment_test_util.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

using cli_test::contains;
using cli_test::Result;
using cli_test::run;
using cli_test::scratch_dir;

// A cube, as a user's model without lights or materials.
constexpr const char* kCubeObj =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

TEST(CliEnvironment, AModelWithoutLightsRendersLitWithAWarning) {
  const fs::path dir = scratch_dir("environment-unlit");
  const fs::path obj = dir / "cube.obj";
  write(obj, kCubeObj);
  const fs::path out = dir / "cube.exr";
  const Result r = run("render " + obj.string() + " -W 16 -H 16 --spp 2 -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "no lights")) << r.output;
  EXPECT_TRUE(contains(r.output, "default sky")) << r.output;
  const Image image = load_image(out.string());
  // The cube's front face in the middle sees half sky (1), half ground (0.25): with albedo 0.8,
  // about 0.5. The sky above it shows radiance 1.
  const vec3 centre = mean(image, 6, 6, 10, 10);
  EXPECT_GT(centre.x, 0.3f) << centre.x;
  EXPECT_LT(centre.x, 0.95f) << centre.x;
  EXPECT_NEAR(image.at(0, 0).x, 1.0f, 1e-3f);
}

TEST(CliEnvironment, SceneFileWithAMapRendersAndABrokenMapIsAnError) {
  const fs::path dir = scratch_dir("environment-map");
  write(dir / "cube.obj", kCubeObj);
  write(dir / "sky.hdr", scene_test::hdr_file(scene_test::synthetic_map(16, 8)));
  write(dir / "broken.hdr",
        std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n\x02\x02\x00\x10\x05"
                    "abc",
                    54));
  const auto scene = [&](const std::string& map) {
    const fs::path path = dir / ("scene-" + map + ".bounce.json");
    write(
        path,
        R"({"models": [{"file": "cube.obj"}], "lights": [{"type": "environment", "map": ")" + map +
            R"(", "rotation_deg": 45}], "camera": {"position": [0, 2, -5], "look_at": [0, 0, 0]}})");
    return path.string();
  };
  const fs::path out = dir / "out.png";
  Result r = run("render " + scene("sky.hdr") + " -W 16 -H 16 --spp 1 -o " + out.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(contains(r.output, "no lights")) << r.output;
  EXPECT_TRUE(fs::exists(out));
  r = run("render " + scene("broken.hdr") + " -W 16 -H 16 --spp 1 -o " + out.string());
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(contains(r.output, "broken.hdr")) << r.output;
  EXPECT_TRUE(contains(r.output, "truncated")) << r.output;
  EXPECT_FALSE(contains(r.output, "terminate")) << r.output;
}

}  // namespace
}  // namespace bounce
