// Batch work across machines, end to end: a reference split into sample slices and run through
// GNU parallel merges into the single run's image; bounce merge refuses slices that do not belong
// together; sequence ranges with a warm-up reproduce the frames of one run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
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

// Per channel within a few float roundings (see docs/scale-out.md: the slices store float means).
void expect_within_float_rounding(const Image& a, const Image& b) {
  ASSERT_EQ(a.pixel_count(), b.pixel_count());
  for (size_t i = 0; i < a.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = a.pixels()[i][c], y = b.pixels()[i][c];
      ASSERT_NEAR(x, y, 4e-7f * std::max(std::fabs(x), std::fabs(y)) + 1e-12f) << i << " " << c;
    }
}

TEST(CliScaleOut, SplitReferenceThroughGnuParallelEqualsOneRun) {
  ASSERT_EQ(std::system("command -v parallel > /dev/null 2>&1"), 0)
      << "GNU parallel is missing: scripts/setup.sh installs Debian's 'parallel'";
  const fs::path dir = scratch_dir("scaleout-reference");
  const std::string common = " reference cornell -W 16 -H 12 --seed 5 -j 1";
  Result r = run(common + " --spp 12 -o " + (dir / "single.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;

  // Three slices of unequal size, two at a time, as on two hosts.
  const std::string slices = (dir / "slice_{1}.exr").string();
  const std::string command = "parallel --will-cite --halt now,fail=1 -j 2 --link " +
                              std::string(BOUNCE_APP_PATH) + common +
                              " --sample-offset {1} --spp {2} -o " + slices +
                              " ::: 0 5 9 ::: 5 4 3 > " + (dir / "parallel.log").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  r = run("merge " + (dir / "merged.exr").string() + " " + (dir / "slice_9.exr").string() + " " +
          (dir / "slice_0.exr").string() + " " + (dir / "slice_5.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "samples 0 .. 11 (12 spp)")) << r.output;
  const Image single = load_image((dir / "single.exr").string());
  expect_within_float_rounding(load_image((dir / "merged.exr").string()), single);
  // A slice alone is a noisier image: the comparison above can tell them apart.
  const Image slice = load_image((dir / "slice_0.exr").string());
  double difference = 0.0;
  for (size_t i = 0; i < single.pixel_count(); ++i)
    difference += std::fabs(slice.pixels()[i].x - single.pixels()[i].x);
  EXPECT_GT(difference / single.pixel_count(), 1e-3);

  // Merging the merged image with a slice counts samples twice.
  r = run("merge " + (dir / "twice.exr").string() + " " + (dir / "merged.exr").string() + " " +
          (dir / "slice_5.exr").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "overlaps")) << r.output;
}

TEST(CliScaleOut, MergeRefusesWhatDoesNotBelongTogether) {
  const fs::path dir = scratch_dir("scaleout-merge-errors");
  const auto slice = [&](const std::string& name, const std::string& args) {
    const Result r = run("reference cornell -H 8 --spp 2 " + args + " -o " + (dir / name).string());
    EXPECT_EQ(r.status, 0) << r.output;
    return (dir / name).string();
  };
  const std::string a = slice("a.exr", "-W 8");
  const std::string other_seed = slice("seed.exr", "-W 8 --seed 9 --sample-offset 2");
  const std::string other_size = slice("size.exr", "-W 9 --sample-offset 2");
  const std::string gap = slice("gap.exr", "-W 8 --sample-offset 4");
  const std::string png = slice("a.png", "-W 8");
  save_image((dir / "plain.exr").string(), Image(8, 8));
  const std::string out = (dir / "out.exr").string();
  const std::pair<std::string, std::string> cases[] = {
      {"merge " + out + " " + a + " " + other_seed, "seed=0"},
      {"merge " + out + " " + a + " " + other_size, "width=8"},
      {"merge " + out + " " + a + " " + gap, "samples 2 .. 3 are missing"},
      {"merge " + out + " " + a + " " + png, "a.png"},
      {"merge " + out + " " + a + " " + (dir / "plain.exr").string(), "not a bounce reference"},
      {"merge " + (dir / "out.png").string() + " " + a, "out.png"},
      {"merge " + out, "inputs"},
  };
  for (const auto& [args, expected] : cases) {
    const Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.status, -1) << args << " crashed";
    EXPECT_TRUE(contains(r.output, expected)) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliScaleOut, SequenceRangesWithWarmupMatchOneRun) {
  const fs::path dir = scratch_dir("scaleout-sequence");
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  const auto sequence = [&](const std::string& name, const std::string& args) {
    const Result r = run("sequence " + scene + " -W 16 -H 16 --fps 10 -j 1 " + args + " -o " +
                         (dir / name / "f_%d.exr").string());
    EXPECT_EQ(r.status, 0) << r.output;
  };
  const auto frame = [&](const std::string& name, int k) {
    return load_image((dir / name / ("f_" + std::to_string(k) + ".exr")).string());
  };
  // State that lasts a bounded number of frames (direct light without the denoiser: none beyond
  // the frame number that seeds the samples): the range equals one run bit for bit.
  sequence("one", "-t direct --no-denoise --from 0 --to 0.6");
  sequence("range", "-t direct --no-denoise --from 0.4 --to 0.6 --warmup 2 --global-numbers");
  for (int k = 4; k <= 6; ++k) EXPECT_EQ(frame("range", k).pixels(), frame("one", k).pixels()) << k;
  EXPECT_FALSE(fs::exists(dir / "range" / "f_3.exr"));            // warm-up frames are not written
  EXPECT_NE(frame("one", 4).pixels(), frame("one", 5).pixels());  // the frames do differ

  // The denoiser's history is a moving average that never ends: a range differs from one run by
  // what the frames before its warm-up left there, less the longer the warm-up (measured at
  // 32x32: linear MSE 3e-4 without warm-up, 7e-5 after 2 frames, 1.4e-6 after 6).
  const auto mse = [](const Image& a, const Image& b) {
    double s = 0.0;
    for (size_t i = 0; i < a.pixel_count(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.pixels()[i][c]) - double(b.pixels()[i][c]);
        s += d * d;
      }
    return s / double(3 * a.pixel_count());
  };
  sequence("denoised", "-t direct --from 0 --to 0.7");
  sequence("cold", "-t direct --from 0.7 --to 0.7 --global-numbers");
  sequence("warm", "-t direct --from 0.7 --to 0.7 --warmup 6 --global-numbers");
  const double cold = mse(frame("cold", 7), frame("denoised", 7));
  const double warm = mse(frame("warm", 7), frame("denoised", 7));
  EXPECT_GT(cold, 0.0);
  EXPECT_LT(warm, 0.1 * cold);
}

}  // namespace
}  // namespace bounce
