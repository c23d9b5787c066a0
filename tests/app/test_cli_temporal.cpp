// bounce bench --flicker / --settle end to end: the text report and the JSON record, against the
// same measurements made in the test.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_test_util.h"
#include "bounce/eval/temporal_runs.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

namespace bounce {
namespace {

using cli_test::contains;
using cli_test::Result;
using cli_test::run;
using cli_test::scratch_dir;

TEST(CliTemporal, BenchReportsFlickerAndSettleAsTextAndJson) {
  const std::filesystem::path dir = scratch_dir("bench-temporal");
  const std::string path = (dir / "bench.json").string();
  const Result r =
      run("bench cornell -t tiled --flicker 4 --settle --settle-frames 8 -W 32 -H 32 --frames 2 "
          "--warmup 1 --json " +
          path);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "flicker (32x32, 4 frames after 1 warm-up)")) << r.output;
  // The same runs made here (bench renders one light sample per pixel unless told otherwise, and
  // denoises with the denoiser's defaults).
  FrameSettings settings;
  settings.width = settings.height = 32;
  settings.light_samples = 1;
  settings.denoise = true;
  const auto tiled = [] { return make_technique("tiled"); };
  const Scene scene = make_cornell();
  const double at_rest = measure_flicker(scene, tiled, settings, 1, 4, true).flicker;
  const double off = measure_flicker(scene, tiled, settings, 1, 4, false).flicker;
  EXPECT_GT(at_rest, 0.0);  // passes at rest still change the image
  EXPECT_TRUE(
      contains(r.output, fmt::format("{:.4f} at rest, {:.4f} with accumulation off", at_rest, off)))
      << r.output;
  EXPECT_TRUE(contains(r.output, "with accumulation off (FrameSettings.accumulate=false)"))
      << r.output;
  EXPECT_TRUE(contains(r.output, "settle (32x32, 16-pixel blocks")) << r.output;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& f = j["flicker"];
  ASSERT_TRUE(f.is_object()) << j.dump(2);
  EXPECT_EQ(f["width"], 32);
  EXPECT_EQ(f["height"], 32);
  EXPECT_EQ(f["frames"], 4);
  EXPECT_NEAR(f["at_rest"].get<double>(), at_rest, 1e-12 * at_rest);
  EXPECT_NEAR(f["accumulation_off"].get<double>(), off, 1e-12 * off);
  EXPECT_FALSE(f.contains("params_turned_off"));  // accumulation is the pipeline's setting
  const nlohmann::json& s = j["settle"];
  ASSERT_TRUE(s.is_object()) << j.dump(2);
  EXPECT_EQ(s["applicable"], true);
  EXPECT_EQ(s["settled"], true);
  EXPECT_GE(s["frames"].get<int>(), 0);
  EXPECT_LE(s["frames"].get<int>(), 8);
  EXPECT_EQ(s["max_frames"], 8);
  EXPECT_EQ(s["tolerance"], 0.05);
  EXPECT_EQ(s["block"], 16);
  EXPECT_EQ(s["errors"].size(), 8u);
  EXPECT_GT(s["change"].get<double>(), 0.0);
  EXPECT_FALSE(s["light"].get<std::string>().empty());
}

TEST(CliTemporal, DirectHasNoSettleAndPlainBenchHasNoTemporalMetrics) {
  const std::filesystem::path dir = scratch_dir("bench-temporal-direct");
  const std::string path = (dir / "bench.json").string();
  Result r =
      run("bench cornell -t direct --flicker 3 --settle -W 16 -H 16 --frames 1 --warmup 0 "
          "--json " +
          path);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "settle: n/a")) << r.output;
  {
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["settle"]["applicable"], false);
    EXPECT_TRUE(j["settle"]["frames"].is_null());
    // Averaging direct light at rest steadies it: less flicker than frames on their own.
    const double at_rest = j["flicker"]["at_rest"].get<double>();
    EXPECT_GT(at_rest, 0.0);
    EXPECT_LT(at_rest, j["flicker"]["accumulation_off"].get<double>());
  }
  r = run("bench cornell -t direct -W 16 -H 16 --frames 1 --warmup 0 --json " + path);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(contains(r.output, "flicker")) << r.output;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["flicker"].is_null());
  EXPECT_TRUE(j["settle"].is_null());
}

TEST(CliTemporal, BadTemporalOptionsAreRejected) {
  for (const char* args : {"bench cornell --flicker -1", "bench cornell --settle-frames 0",
                           "bench cornell --settle-tolerance -0.5"}) {
    const Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.status, -1) << args << " crashed";
  }
}

}  // namespace
}  // namespace bounce
