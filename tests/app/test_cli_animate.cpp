// bounce bench --animate: frames are the scene posed along its animation, the scene stage holds
// posing and refitting; a still scene is refused. render --at poses the scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_test_util.h"
#include "bounce/core/image_io.h"

namespace bounce {
namespace {

using cli_test::contains;
using cli_test::Result;
using cli_test::run;

// Photons stored per frame, from `bench ... --json`. Without accumulation tiled's photon paths
// follow the frame index, so this depends only on the poses and the indices of the frames.
double stored_photons_per_frame(const std::string& args) {
  const std::filesystem::path dir = cli_test::scratch_dir("bench-animate");
  const std::string path = (dir / "bench.json").string();
  const Result r = run("bench " + args + " --json " + path);
  EXPECT_EQ(r.status, 0) << args << "\n" << r.output;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  return j["photons"]["stored_per_frame"].get<double>();
}

TEST(CliAnimate, BenchPlaysTheAnimationAndTimesTheSceneStage) {
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  const Result r = run("bench " + scene + " -W 32 -H 32 --frames 3 --warmup 1 --animate");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "3 frames after 1 warm-up")) << r.output;
  EXPECT_TRUE(contains(r.output, ", animated")) << r.output;
  // The stage table has the scene stage, where posing and refitting are timed.
  EXPECT_TRUE(contains(r.output, "\nscene ")) << r.output;

  // Frame k of an animated bench is the scene posed at --at + k/30 s: two animated frames store
  // the photons of the two poses, each rendered still as the same frame (0, or 1 after a warm-up
  // frame).
  const std::string tiled = scene + " -t tiled -W 16 -H 16";
  const double first = stored_photons_per_frame(tiled + " --warmup 0 --frames 1 --at 0");
  const double second =
      stored_photons_per_frame(tiled + " --warmup 1 --frames 1 --at 0.0333333351");
  ASSERT_NE(first, second) << "the two poses must differ for the test to see the animation";
  const double animated =
      stored_photons_per_frame(tiled + " --warmup 0 --frames 2 --at 0 --animate");
  EXPECT_EQ(animated, 0.5 * (first + second));
}

TEST(CliAnimate, AStillSceneIsRefused) {
  const Result r = run("bench cornell -W 16 -H 16 --frames 1 --animate");
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(contains(r.output, "cornell: --animate: the scene has no animation")) << r.output;
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
