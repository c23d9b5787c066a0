// The soak in small (scripts/soak.sh runs 10,000 frames at 64x64 with default parameters;
// docs/reliability.md): `bench --animate --memory-every` plays the dynamic Cornell box (a moving
// light and a moving cube) with each technique and samples resident memory; after warm-up it must
// stay flat.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/cli_test_util.h"

namespace bounce {
namespace {

using cli_test::Result;
using cli_test::run;

// Sets an environment variable for the programs the test starts, and restores it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

constexpr int kWarmup = 100, kFrames = 200, kEvery = 10;
// Allowed growth of resident memory after warm-up: a leak of 5 KB a frame (a 16x16 frame buffer
// is 3 KB) exceeds it over 200 frames. Measured growth in a Release build is below 0.1 MiB.
constexpr double kMaxGrowthBytes = 1.0 * 1024 * 1024;

// Each technique, with its data made small so that 300 frames take a second or two: vertex's
// photon ring (4 frames) and lhb's hit buffers fill within the warm-up.
struct SoakCase {
  const char* technique;
  const char* options;
};
constexpr SoakCase kCases[] = {
    {"direct", ""},
    {"tiled", "--photons 500"},
    {"vertex",
     "--refine 100 --accumulation-frames 4 --photons-from-light 20 -p diffuse_reflections=8"},
    {"lhb", "-p size=16 -p directions=20"},
};

TEST(CliSoak, ResidentMemoryStaysFlatAfterWarmupWithEveryTechnique) {
  // Under AddressSanitizer freed memory sits in a quarantine that fills over the run; without it
  // the sanitized build measures the same thing. No effect on other builds.
  const ScopedEnv asan("ASAN_OPTIONS", "quarantine_size_mb=0:detect_leaks=1");
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  const std::filesystem::path dir = cli_test::scratch_dir("soak");
  for (const SoakCase& c : kCases) {
    const std::string technique = c.technique;
    const std::string json = (dir / (technique + ".json")).string();
    const Result r = run("bench " + scene + " -t " + technique + " " + c.options +
                         " -W 16 -H 16 --animate --warmup " + std::to_string(kWarmup) +
                         " --frames " + std::to_string(kFrames) + " --memory-every " +
                         std::to_string(kEvery) + " --json " + json);
    ASSERT_EQ(r.status, 0) << technique << "\n" << r.output;
    EXPECT_TRUE(cli_test::contains(r.output, "resident memory")) << r.output;
    std::ifstream in(json);
    const nlohmann::json m = nlohmann::json::parse(in)["resident_memory"];
    const auto frames = m["frames"].get<std::vector<int>>();
    const auto bytes = m["bytes"].get<std::vector<double>>();
    ASSERT_EQ(frames.size(), size_t((kWarmup + kFrames) / kEvery)) << technique;
    ASSERT_EQ(frames.front(), kEvery);
    ASSERT_EQ(frames.back(), kWarmup + kFrames);
    double base = 0.0, peak = 0.0;
    for (size_t i = 0; i < frames.size(); ++i) {
      EXPECT_GT(bytes[i], 1e6) << technique << ": a process holds more than 1 MB";
      if (frames[i] < kWarmup) continue;
      if (base == 0.0) base = bytes[i];
      peak = std::max(peak, bytes[i]);
    }
    EXPECT_LE(peak - base, kMaxGrowthBytes)
        << technique << ": resident memory grew from " << base << " to " << peak << " bytes";
    EXPECT_NEAR(m["growth_after_warmup"].get<double>(), peak / base - 1.0, 1e-9) << technique;
  }
}

}  // namespace
}  // namespace bounce
