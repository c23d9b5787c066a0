// bounce bench --animate: the scene stage holds posing and refitting; a still scene is refused.
#include <gtest/gtest.h>

#include <string>

#include "app/cli_test_util.h"

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
