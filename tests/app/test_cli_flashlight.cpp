// --flashlight on the command line: render, sequence and reference carry the viewer's flashlight,
// and a sequence moves it along the camera path with the camera.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_test_util.h"
#include "bounce/core/image_io.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using cli_test::Result;
using cli_test::run;
using cli_test::scratch_dir;

double mean_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixel_count(), b.pixel_count());
  double sum = 0.0;
  for (size_t i = 0; i < a.pixel_count(); ++i) sum += glm::length(a.pixels()[i] - b.pixels()[i]);
  return sum / double(a.pixel_count());
}

double mean_value(const Image& a) {
  double sum = 0.0;
  for (const vec3& p : a.pixels()) sum += double(p.x + p.y + p.z);
  return sum / double(a.pixel_count());
}

TEST(CliFlashlight, SequenceCarriesItAlongTheCameraPath) {
  const fs::path dir = scratch_dir("flashlight-path");
  // The walk's path goes from the Cornell camera (t 0) to a pose looking at the left wall (t 1).
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/cornell-walk.bounce.json";
  const std::string common = " -t direct --light-samples 16 -W 32 -H 32 --no-denoise";
  Result r = run("sequence " + scene + common + " --flashlight --from 0 --to 1 --fps 1 -o " +
                 (dir / "seq_%d.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto render = [&](const std::string& at, bool flashlight) {
    const std::string out =
        (dir / ("render-" + at + (flashlight ? "-flash" : "") + ".exr")).string();
    const Result rr = run("render " + scene + common + " --spp 1 --at " + at +
                          (flashlight ? " --flashlight" : "") + " -o " + out);
    EXPECT_EQ(rr.status, 0) << rr.output;
    return load_image(out);
  };
  const Image first = load_image((dir / "seq_0.exr").string());
  const Image second = load_image((dir / "seq_1.exr").string());
  const Image a_lit = render("0", true), b_lit = render("1", true), b_dark = render("1", false);

  // The flashlight adds light where the camera looks.
  EXPECT_GT(mean_value(b_lit), 1.05 * mean_value(b_dark));
  // Frame 0: the same frame as render's at the path's start, flashlight included.
  EXPECT_LT(mean_difference(first, a_lit), 1e-6 * mean_difference(b_lit, a_lit));
  // Frame 1: the flashlight went with the camera to pose B; it matches render's there (up to
  // the noise of a frame with history) far better than the same view without it.
  const double match = mean_difference(second, b_lit);
  EXPECT_LT(match, 0.2 * mean_difference(second, b_dark)) << match;
}

// A flashlight carried along the walk, with the denoiser: its light is shaded apart while it
// moves (the JSON says so), and --moving-lights-in-history averages it with the rest instead,
// which leaves another displayed frame.
TEST(CliFlashlight, SequenceShadesItApartWhileItMoves) {
  const fs::path dir = scratch_dir("flashlight-apart");
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/cornell-walk.bounce.json";
  const auto last_frame = [&](const std::string& name, const std::string& flags) {
    const std::string json = (dir / (name + ".json")).string();
    const Result r = run("sequence " + scene + " -t direct -W 32 -H 32 --flashlight --from 0 " +
                         "--to 1 --fps 8 --every 8 -o " + (dir / (name + "_%d.exr")).string() +
                         " --json " + json + flags);
    EXPECT_EQ(r.status, 0) << r.output;
    std::ifstream in(json);
    EXPECT_EQ(nlohmann::json::parse(in)["moving_lights"], flags.empty() ? "apart" : "history");
    return load_image((dir / (name + "_8.exr")).string());
  };
  const Image apart = last_frame("apart", ""),
              in_history = last_frame("history", " --moving-lights-in-history");
  EXPECT_GT(mean_difference(apart, in_history), 1e-4 * mean_value(apart));
}

TEST(CliFlashlight, ReferenceAndBenchTakeIt) {
  const fs::path dir = scratch_dir("flashlight-reference");
  const auto reference = [&](bool flashlight) {
    const std::string out = (dir / (flashlight ? "flash.exr" : "plain.exr")).string();
    const Result r = run("reference cornell -W 16 -H 16 --spp 16 -o " + out +
                         (flashlight ? " --flashlight" : ""));
    EXPECT_EQ(r.status, 0) << r.output;
    return load_image(out);
  };
  EXPECT_GT(mean_value(reference(true)), 1.05 * mean_value(reference(false)));
  const Result bench = run("bench cornell -t vertex -W 16 -H 16 -n 2 --warmup 1 --flashlight");
  EXPECT_EQ(bench.status, 0) << bench.output;
}

}  // namespace
}  // namespace bounce
