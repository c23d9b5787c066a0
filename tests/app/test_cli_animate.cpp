// bounce bench --animate: the scene stage holds posing and refitting; a still scene is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/cli_test_util.h"
#include "bounce/core/image_io.h"

namespace bounce {
namespace {

using cli_test::Result;
using cli_test::run;

TEST(CliAnimate, BenchPlaysTheAnimationAndTimesTheSceneStage) {
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  const Result r = run("bench " + scene + " -W 32 -H 32 --frames 3 --warmup 1 --animate");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(", animated"), std::string::npos) << r.output;
  // The scene stage's mean is printed and is not zero: the cube is posed and refitted.
  const size_t row = r.output.find("\nscene ");
  ASSERT_NE(row, std::string::npos) << r.output;
  const double mean = std::stod(r.output.substr(row + 7));
  EXPECT_GT(mean, 0.0) << r.output;
}

TEST(CliAnimate, AStillSceneIsRefused) {
  const Result r = run("bench cornell -W 16 -H 16 --frames 1 --animate");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("cornell: --animate: the scene has no animation"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace bounce

namespace bounce {
namespace {

TEST(CliAnimate, RenderPosesTheSceneAtTheGivenTime) {
  const std::filesystem::path dir = cli_test::scratch_dir("render-at");
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  const auto render_at = [&](const std::string& at) {
    const std::string out = (dir / ("at" + at + ".pfm")).string();
    const Result r =
        run("render " + scene + " -t direct -W 24 -H 24 --spp 1 --at " + at + " -o " + out);
    EXPECT_EQ(r.status, 0) << r.output;
    return load_image(out);
  };
  const Image a = render_at("0"), b = render_at("1"), c = render_at("4");
  double ab = 0.0, ac = 0.0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    ab += glm::length(a.pixels()[i] - b.pixels()[i]);
    ac += glm::length(a.pixels()[i] - c.pixels()[i]);
  }
  EXPECT_GT(ab, 0.0);  // the cube and the bulb moved
  EXPECT_EQ(ac, 0.0);  // the 4-second loop is back at its start
  EXPECT_NE(run("render cornell --at -1").status, 0);
}

}  // namespace
}  // namespace bounce
