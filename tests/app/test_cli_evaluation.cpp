// The evaluation commands end to end: reference, compare and bench --json, whose numbers must
// agree with what was asked and with each other.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli_test_util.h"
#include "bounce/core/image_io.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

using cli_test::contains;
using cli_test::Result;
using cli_test::run;
using cli_test::scratch_dir;

TEST(CliEvaluation, CommandsHaveHelp) {
  for (const char* command : {"reference", "compare"}) {
    const Result r = run(std::string(command) + " --help");
    EXPECT_EQ(r.status, 0) << command << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, "Usage")) << command;
  }
}

TEST(CliEvaluation, ReferenceWritesALinearImageAndReportsProgress) {
  const fs::path dir = scratch_dir("reference");
  const fs::path exr = dir / "ref.exr";
  const Result r =
      run("reference cornell --spp 4 --width 24 --height 16 --max-bounces 1 --out " + exr.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "100% (4/4 spp)")) << r.output;
  EXPECT_TRUE(contains(r.output, "ETA")) << r.output;
  EXPECT_TRUE(contains(r.output, "max bounces 1")) << r.output;
  const bounce::Image image = bounce::load_image(exr.string());
  EXPECT_EQ(image.width(), 24);
  EXPECT_EQ(image.height(), 16);
  const bounce::vec3 m = bounce::mean(image);
  for (int c = 0; c < 3; ++c) EXPECT_GT(m[c], 0.0f) << c;
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1) << "no temporary files left behind";
}

TEST(CliEvaluation, ReferenceRejectsBadArguments) {
  const std::pair<const char*, const char*> cases[] = {
      {"reference --spp 0", "spp"},
      {"reference --max-bounces -2", "max-bounces"},
      {"reference --time -1", "time"},
      {"reference -W 8 -H 8 --spp 1 --out ref.bmp", "ref.bmp"},
      {"reference /nonexistent/scene.obj", "/nonexistent/scene.obj"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.status, -1) << args << " crashed";
    EXPECT_TRUE(contains(r.output, expected)) << args << "\n" << r.output;
  }
}

TEST(CliEvaluation, CompareReportsMetricsAsTextAndJson) {
  const fs::path dir = scratch_dir("compare");
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.pfm").string();
  const std::string heat = (dir / "heat.png").string();
  bounce::Image image(16, 12, bounce::vec3(0.5f));
  image.at(0, 0) = bounce::vec3(0.0f);
  image.at(1, 0) = bounce::vec3(1.0f);
  bounce::save_image(a, image);
  image.at(3, 3).x += 0.25f;
  bounce::save_image(b, image);

  Result r = run("compare " + a + " " + a);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "MSSIM")) << r.output;
  EXPECT_TRUE(contains(r.output, "inf")) << r.output;  // PSNR of identical images
  EXPECT_TRUE(contains(r.output, "FLIP           0.000000")) << r.output;

  const std::string flip = (dir / "flip.png").string();
  r = run("compare " + a + " " + b + " --json --heatmap " + heat + " --flip-map " + flip, false);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["width"], 16);
  EXPECT_EQ(j["height"], 12);
  EXPECT_DOUBLE_EQ(j["linear"]["mse"].get<double>(), 0.25 * 0.25 / (3.0 * 16 * 12));
  EXPECT_DOUBLE_EQ(j["linear"]["range"].get<double>(), 1.0);
  EXPECT_GT(j["srgb8"]["mse"].get<double>(), 0.0);
  EXPECT_LT(j["srgb8"]["mssim"].get<double>(), 1.0);
  EXPECT_EQ(j["heatmap"]["path"], heat);
  const bounce::Image h = bounce::load_image(heat);
  EXPECT_EQ(h.width(), 16);
  // One pixel of 192 differs, so the mean FLIP is small but not 0; the map is grey and brightest
  // at that pixel.
  EXPECT_GT(j["flip"]["mean"].get<double>(), 0.0);
  EXPECT_LT(j["flip"]["mean"].get<double>(), 0.05);
  EXPECT_NEAR(j["flip"]["ppd"].get<double>(), 67.02, 0.01);
  const bounce::Image f = bounce::load_image(flip);
  ASSERT_EQ(f.width(), 16);
  EXPECT_EQ(f.at(3, 3).x, f.at(3, 3).y);
  for (const bounce::vec3& p : f.pixels()) EXPECT_LE(p.x, f.at(3, 3).x);
  EXPECT_GT(f.at(3, 3).x, 0.0f);

  r = run("compare " + a + " " + a + " --json", false);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(nlohmann::json::parse(r.output)["linear"]["psnr_db"].is_null());
}

TEST(CliEvaluation, CompareRejectsMismatchedAndMissingImages) {
  const fs::path dir = scratch_dir("compare-errors");
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  bounce::save_image(a, bounce::Image(8, 8));
  bounce::save_image(b, bounce::Image(8, 9));
  const std::pair<std::string, std::string> cases[] = {
      {"compare " + a + " " + b, "sizes differ"},
      {"compare " + a + " " + (dir / "missing.exr").string(), "missing.exr"},
      {"compare " + a, "test"},
      {"compare " + a + " " + a + " --heatmap " + (dir / "h.exr").string(), "h.exr"},
      {"compare " + a + " " + a + " --flip-map " + (dir / "f.exr").string(), "f.exr"},
      {"compare " + a + " " + a + " --flip-ppd 0", "--flip-ppd"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.status, -1) << args << " crashed";
    EXPECT_TRUE(contains(r.output, expected)) << args << "\n" << r.output;
  }
}

// The stage table of a bench JSON record: name -> (mean, standard deviation) in ms.
std::map<std::string, std::pair<double, double>> stage_table(const nlohmann::json& j) {
  std::map<std::string, std::pair<double, double>> table;
  for (const auto& stage : j["stages"])
    table[stage["name"].get<std::string>()] = {stage["mean_ms"].get<double>(),
                                               stage["stddev_ms"].get<double>()};
  return table;
}

// What must hold between a bench record's numbers whatever the timings: the top-level stages
// add up to the frame total, each standard deviation is one that non-negative times can have,
// and every rate is its count over the time of the stage it is measured on.
void expect_consistent_timings(const nlohmann::json& j) {
  const double frames = j["frames"].get<double>();
  const double total = j["total"]["mean_ms"].get<double>();
  ASSERT_GT(total, 0.0);
  double sum = 0.0;
  for (const auto& [name, timing] : stage_table(j)) {
    const auto [mean, stddev] = timing;
    if (!contains(name, "/")) sum += mean;  // "indirect/..." sub-stages lie inside "indirect"
    // n times >= 0 with mean m have a sample deviation of at most m sqrt(n).
    EXPECT_LE(stddev, mean * std::sqrt(frames) * (1.0 + 1e-9) + 1e-12) << name;
  }
  EXPECT_NEAR(sum, total, 1e-9 * total);
  EXPECT_NEAR(j["fps"].get<double>(), 1000.0 / total, 1e-9 * (1000.0 / total));
  const auto table = stage_table(j);
  const auto rate = [&](const char* count, const char* stage) {
    return j["rays"][count].get<double>() / (table.at(stage).first * 1e-3);
  };
  const nlohmann::json& rays = j["rays"];
  EXPECT_NEAR(rays["primary_per_s"].get<double>(), rate("primary_per_frame", "gbuffer"),
              1e-9 * rays["primary_per_s"].get<double>());
  EXPECT_NEAR(rays["shadow_per_s"].get<double>(), rate("shadow_per_frame", "direct"),
              1e-9 * rays["shadow_per_s"].get<double>());
}

TEST(CliEvaluation, BenchWritesJson) {
  const fs::path dir = scratch_dir("bench-json");
  const std::string path = (dir / "bench.json").string();
  const Result r = run("bench cornell -t direct -W 16 -H 16 --frames 3 --warmup 1 --json " + path);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["scene"], "cornell");
  EXPECT_EQ(j["technique"], "direct");
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["warmup_frames"], 1);
  EXPECT_EQ(j["width"], 16);
  EXPECT_EQ(j["height"], 16);
  EXPECT_EQ(j["light_samples"], 1);  // bench's real-time default
  EXPECT_EQ(j["shadow_rays"], "one");  // --shadow-rays auto with one light sample
  EXPECT_FALSE(j["bounce_version"].get<std::string>().empty());
  EXPECT_FALSE(j["build"]["compiler"].get<std::string>().empty());
  EXPECT_TRUE(j["build"]["git_revision_at_configure"].is_string());
  EXPECT_FALSE(j["machine"]["cpu"].get<std::string>().empty());
  EXPECT_GE(j["machine"]["logical_cores"].get<int>(), 1);
  EXPECT_GE(j["machine"]["threads"].get<int>(), 1);

  const auto stages = stage_table(j);
  for (const char* stage : {"gbuffer", "direct", "composite", "tonemap"})
    EXPECT_EQ(stages.count(stage), 1u) << stage;
  EXPECT_EQ(stages.count("indirect"), 0u) << "direct has no indirect stage";
  expect_consistent_timings(j);

  // One primary ray per pixel; at most one shadow ray per pixel (one area light, one sample),
  // and some pixels see the light above their horizon.
  EXPECT_EQ(j["rays"]["primary_per_frame"].get<double>(), 16.0 * 16.0);
  EXPECT_GT(j["rays"]["shadow_per_frame"].get<double>(), 0.0);
  EXPECT_LE(j["rays"]["shadow_per_frame"].get<double>(), 16.0 * 16.0);
  // No technique, no photons: counts of zero and no rate over a stage that did not run.
  EXPECT_EQ(j["rays"]["technique_per_frame"].get<double>(), 0.0);
  EXPECT_TRUE(j["rays"]["technique_per_s"].is_null());
  EXPECT_EQ(j["photons"]["paths_per_frame"].get<double>(), 0.0);
  EXPECT_EQ(j["photons"]["stored_per_frame"].get<double>(), 0.0);
  EXPECT_TRUE(j["photons"]["paths_per_s"].is_null());
  EXPECT_TRUE(j["flicker"].is_null());
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(CliEvaluation, BenchJsonCountsThePhotonsAskedFor) {
  const fs::path dir = scratch_dir("bench-json-tiled");
  const std::string path = (dir / "bench.json").string();
  const Result r =
      run("bench cornell -t tiled -W 16 -H 16 --light-samples 2 --frames 2 --warmup 0 "
          "--param photons=500 --json " +
          path);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["technique"], "tiled");
  EXPECT_EQ(j["params"]["photons"], "500");
  EXPECT_EQ(j["light_samples"], 2);
  EXPECT_EQ(j["shadow_rays"], "all");  // auto with two light samples
  EXPECT_EQ(j["frames"], 2);
  EXPECT_EQ(stage_table(j).count("indirect"), 1u);
  expect_consistent_timings(j);
  EXPECT_EQ(j["rays"]["primary_per_frame"].get<double>(), 16.0 * 16.0);
  EXPECT_LE(j["rays"]["shadow_per_frame"].get<double>(), 2.0 * 16.0 * 16.0);
  const nlohmann::json& photons = j["photons"];
  const double paths = photons["paths_per_frame"].get<double>();
  EXPECT_EQ(paths, 500.0);
  EXPECT_GT(photons["stored_per_frame"].get<double>(), 0.0);
  // Every path traces at least the ray it leaves its light on.
  EXPECT_GE(j["rays"]["technique_per_frame"].get<double>(), paths);
  // Photon paths and technique rays are rated over the technique's stages, prepare (photon
  // tracing) and indirect (estimation).
  const double indirect_s =
      (stage_table(j).at("prepare").first + stage_table(j).at("indirect").first) * 1e-3;
  EXPECT_NEAR(photons["paths_per_s"].get<double>(), paths / indirect_s, 1e-9 * paths / indirect_s);
  const double technique_rate = j["rays"]["technique_per_frame"].get<double>() / indirect_s;
  EXPECT_NEAR(j["rays"]["technique_per_s"].get<double>(), technique_rate, 1e-9 * technique_rate);
}

}  // namespace
}  // namespace bounce
