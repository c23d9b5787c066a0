// The command-line program end to end: help, bad arguments, missing files, and real output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
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

TEST(Cli, EveryCommandHasHelp) {
  for (const char* command : {"", "render", "info", "bench"}) {
    const Result r = run(std::string(command) + " --help");
    EXPECT_EQ(r.status, 0) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << command;
  }
}

TEST(Cli, BadArgumentsAreRejectedWithAMessage) {
  const std::pair<const char*, const char*> cases[] = {
      {"", "subcommand"},
      {"frobnicate", "subcommand"},
      {"render --width -5", "width"},
      {"render --width abc", "width"},
      {"render --light-samples 0", "light-samples"},
      {"render -W 8 -H 8 --shadow-rays some", "shadow-rays"},
      {"render --technique nonsense -W 8 -H 8", "unknown technique 'nonsense'"},
      {"render --param nope=1 -W 8 -H 8", "unknown parameter 'nope'"},
      {"render --out out.bmp -W 8 -H 8", "out.bmp"},
      {"render cubes:abc", "cubes:abc"},
      {"info", "scene"},
      {"bench cornell --frames 0", "frames"},
      {"render -W 8 -H 8 --radius abc", "radius"},
      {"render -W 8 -H 8 --radius 5x%", "percentage"},
      {"render -W 8 -H 8 --gather nope", "gather"},
      {"render -W 8 -H 8 -t direct --photons 10",
       "technique 'direct': --photons is not an option of this technique"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.status, -1) << args << " crashed";
    EXPECT_NE(r.output.find(expected), std::string::npos) << args << "\n" << r.output;
  }
}

// tiled declares its own options; each sets the parameter it names, as bench's JSON records.
TEST(Cli, TechniqueOptionsReachTheTechnique) {
  const fs::path dir = scratch_dir("photons");
  const std::string json = (dir / "bench.json").string();
  const Result r =
      run("bench cornell -W 24 -H 24 --frames 2 --warmup 0 --photons 500 --radius 4% "
          "--bounces 2 --lowres 3 --tile 4 --gather grid --json " +
          json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("indirect/hash grid"), std::string::npos) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& p = j["params"];
  EXPECT_EQ(p["photons"], "500");
  EXPECT_EQ(p["radius"], "0");
  EXPECT_EQ(p["radius_rel"], "0.04");
  EXPECT_EQ(p["bounces"], "2");
  EXPECT_EQ(p["lowres"], "3");
  EXPECT_EQ(p["tile"], "4");
  EXPECT_EQ(p["gather"], "1");
  EXPECT_EQ(j["photons"]["paths_per_frame"], 500.0);
  // An absolute radius goes to `radius`; the relative one keeps its default.
  const Result abs =
      run("bench cornell -W 8 -H 8 --frames 1 --warmup 0 --radius 0.25 --json " + json);
  ASSERT_EQ(abs.status, 0) << abs.output;
  std::ifstream in2(json);
  const nlohmann::json k = nlohmann::json::parse(in2);
  EXPECT_EQ(k["params"]["radius"], "0.25");
  EXPECT_EQ(k["params"]["radius_rel"], "0.03");
  EXPECT_EQ(k["params"]["photons"], "2000");  // bench keeps the real-time default
}

// A still affords more photons per pass than a real-time frame, unless the user says otherwise.
TEST(Cli, RenderAppliesTheTechniquesStillDefaultsUnderTheUsersOptions) {
  const fs::path dir = scratch_dir("still");
  const std::string out = (dir / "t.png").string();
  Result r = run("render -W 8 -H 8 --spp 1 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(" photons=20000 "), std::string::npos) << r.output;
  r = run("render -W 8 -H 8 --spp 1 --photons 300 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(" photons=300 "), std::string::npos) << r.output;
  r = run("render -W 8 -H 8 --spp 1 -p photons=400 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(" photons=400 "), std::string::npos) << r.output;
}

TEST(Cli, MissingSceneFileIsNamed) {
  const Result r = run("render /nonexistent/dir/scene.obj -W 8 -H 8");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/dir/scene.obj"), std::string::npos) << r.output;
}

TEST(Cli, RenderWritesPngAndExrAndPrintsStageTimes) {
  const fs::path dir = scratch_dir("render");
  const fs::path png = dir / "cornell.png", exr = dir / "cornell.exr";
  Result r = run("render -W 32 -H 24 --spp 2 --light-samples 2 --out " + png.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* stage : {"gbuffer", "direct", "composite", "tonemap", "total"})
    EXPECT_NE(r.output.find(stage), std::string::npos) << stage << "\n" << r.output;
  r = run("render cornell -W 32 -H 24 --light-samples 2 --out " + exr.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const bounce::Image a = bounce::load_image(png.string());
  const bounce::Image b = bounce::load_image(exr.string());
  EXPECT_EQ(a.width(), 32);
  EXPECT_EQ(a.height(), 24);
  EXPECT_EQ(b.width(), 32);
  EXPECT_GT(bounce::mean(b).x, 0.0f);
  // Only the two images: no temporary files left beside them.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2);
}

TEST(Cli, InfoAndBenchReportTheScene) {
  Result r = run("info cornell");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("triangles   32"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("MiB"), std::string::npos) << r.output;
  r = run("bench cornell -W 16 -H 16 --frames 3 --warmup 1");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("stddev"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("primary rays/s"), std::string::npos) << r.output;
}

// --shadow-rays: one ray per light sample (all), one per pixel (one), or one exactly when there is
// one light sample (auto, the default), as bench counts them.
TEST(Cli, ShadowRaysOptionSetsTheRaysPerPixel) {
  auto rays_per_frame = [](const std::string& options) {
    const Result r = run("bench cornell -W 16 -H 16 --frames 1 --warmup 0 " + options);
    EXPECT_EQ(r.status, 0) << r.output;
    const size_t end = r.output.find(" shadow rays per frame");
    const size_t start = r.output.rfind('(', end);
    if (end == std::string::npos || start == std::string::npos) return -1L;
    return std::stol(r.output.substr(start + 1, end - start - 1));
  };
  const long one_sample = rays_per_frame(""), four_all = rays_per_frame("--light-samples 4"),
             four_one = rays_per_frame("--light-samples 4 --shadow-rays one"),
             one_all = rays_per_frame("--shadow-rays all");
  ASSERT_GT(one_sample, 0);
  EXPECT_LE(one_sample, 16 * 16);
  EXPECT_EQ(one_all, one_sample);  // a single sample is traced either way
  EXPECT_GT(four_all, 3 * one_sample);
  // At most one per pixel (a pixel whose single sample fell behind the light may find one of four).
  EXPECT_LE(four_one, 16 * 16);
  EXPECT_GE(four_one, one_sample);
}

}  // namespace
}  // namespace bounce
