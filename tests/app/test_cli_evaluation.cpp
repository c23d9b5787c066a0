// The evaluation commands end to end: reference, compare and bench --json.
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

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

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
  EXPECT_GT(bounce::mean(image).x, 0.0f);
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

  r = run("compare " + a + " " + b + " --json --heatmap " + heat, false);
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
  };
  for (const auto& [args, expected] : cases) {
    const Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.status, -1) << args << " crashed";
    EXPECT_TRUE(contains(r.output, expected)) << args << "\n" << r.output;
  }
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
  EXPECT_EQ(j["width"], 16);
  EXPECT_FALSE(j["bounce_version"].get<std::string>().empty());
  EXPECT_FALSE(j["build"]["compiler"].get<std::string>().empty());
  EXPECT_TRUE(j["build"].contains("git_revision_at_configure"));
  EXPECT_FALSE(j["machine"]["cpu"].get<std::string>().empty());
  EXPECT_GE(j["machine"]["logical_cores"].get<int>(), 1);
  bool has_gbuffer = false;
  for (const auto& stage : j["stages"]) {
    EXPECT_GE(stage["mean_ms"].get<double>(), 0.0);
    EXPECT_GE(stage["stddev_ms"].get<double>(), 0.0);
    has_gbuffer |= stage["name"] == "gbuffer";
  }
  EXPECT_TRUE(has_gbuffer);
  EXPECT_GT(j["total"]["mean_ms"].get<double>(), 0.0);
  EXPECT_EQ(j["rays"]["primary_per_frame"].get<double>(), 256.0);
  EXPECT_GT(j["rays"]["primary_per_s"].get<double>(), 0.0);
  EXPECT_TRUE(j["photons"].contains("paths_per_s"));
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace bounce
