// bounce sequence end to end: the frames it names and nothing else, refusals before any file is
// written, no half-written file when writing fails, and frames posed along the camera path and
// the animation.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
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

// The names of the entries of a directory (none when it does not exist).
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// Mean over pixels of the length of the colour difference.
double mean_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  double sum = 0.0;
  for (size_t i = 0; i < a.pixel_count(); ++i) sum += glm::length(a.pixels()[i] - b.pixels()[i]);
  return sum / double(a.pixel_count());
}

TEST(CliSequence, WritesExactlyTheFramesItNames) {
  const fs::path dir = scratch_dir("sequence-frames");
  const std::string json = (dir / "run.json").string();
  // Still scenes play for --to seconds; 0.2 s at 10 fps is frames 0, 1 and 2 (t = 0, 0.1, 0.2).
  Result r = run("sequence cornell -W 32 -H 32 --to 0.2 --fps 10 -o " +
                 (dir / "all" / "f_%04d.png").string() + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(entries(dir / "all"),
            (std::set<std::string>{"f_0000.png", "f_0001.png", "f_0002.png"}));
  for (const auto& name : entries(dir / "all")) {
    const Image image = load_image((dir / "all" / name).string());
    EXPECT_EQ(image.width(), 32);
    EXPECT_EQ(image.height(), 32);
  }
  EXPECT_TRUE(contains(r.output, "3 frames rendered, 3 written")) << r.output;
  EXPECT_TRUE(contains(r.output, "technique tiled 32x32, 1 light samples")) << r.output;

  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["frames_rendered"], 3);
  EXPECT_EQ(j["frames_written"], 3);
  ASSERT_EQ(j["frames"].size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const nlohmann::json& f = j["frames"][size_t(k)];
    EXPECT_EQ(f["index"], k);
    EXPECT_NEAR(f["time"].get<double>(), 0.1 * k, 1e-12);
    EXPECT_GT(f["ms"].get<double>(), 0.0);
    EXPECT_EQ(f["file"], (dir / "all" / fmt::format("f_{:04}.png", k)).string());
  }
  // The means: of every frame, and of those after the first (which also sizes the buffers).
  const double ms[3] = {j["frames"][0]["ms"], j["frames"][1]["ms"], j["frames"][2]["ms"]};
  EXPECT_NEAR(j["mean_frame_ms"].get<double>(), (ms[0] + ms[1] + ms[2]) / 3.0, 1e-9);
  EXPECT_NEAR(j["mean_frame_ms_after_first"].get<double>(), (ms[1] + ms[2]) / 2.0, 1e-9);
  EXPECT_TRUE(contains(r.output, "mean frame after the first")) << r.output;

  // --every 2 keeps frames 0 and 2; frame 1 is still rendered (and timed) for the history.
  r = run("sequence cornell -W 32 -H 32 --to 0.2 --fps 10 --every 2 -o " +
          (dir / "every" / "f_%d.exr").string() + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(entries(dir / "every"), (std::set<std::string>{"f_0.exr", "f_2.exr"}));
  for (const auto& name : entries(dir / "every")) {
    const Image image = load_image((dir / "every" / name).string());
    ASSERT_EQ(image.width(), 32);
    ASSERT_EQ(image.height(), 32);
    double sum = 0.0;
    for (const vec3& p : image.pixels()) sum += p.x + p.y + p.z;
    EXPECT_GT(sum, 0.0) << name;  // linear radiance, not an empty frame
  }
  EXPECT_TRUE(contains(r.output, "3 frames rendered, 2 written (every 2)")) << r.output;
  std::ifstream again(json);
  const nlohmann::json e = nlohmann::json::parse(again);
  EXPECT_EQ(e["frames_rendered"], 3);
  EXPECT_EQ(e["frames_written"], 2);
  ASSERT_EQ(e["frames"].size(), 3u);
  EXPECT_FALSE(e["frames"][1].contains("file"));

  // A range that floating point misses by a rounding error: 0.3 - 0.1 is 1.9999999999999998
  // frames at 10 fps; the frame at --to is still there.
  r = run("sequence cornell -t direct -W 8 -H 8 --from 0.1 --to 0.3 --fps 10 -o " +
          (dir / "rounding" / "f_%d.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(entries(dir / "rounding"), (std::set<std::string>{"f_0.png", "f_1.png", "f_2.png"}));
}

TEST(CliSequence, AnimatedSceneRunsToTheEndOfItsAnimationByDefault) {
  const fs::path dir = scratch_dir("sequence-default-to");
  const std::string scene = std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  // The animation lasts 4 s: from 3.5 s at 2 fps that is frames at 3.5 and 4.
  const Result r = run("sequence " + scene + " -t direct -W 8 -H 8 --from 3.5 --fps 2 -o " +
                       (dir / "f_%d.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(entries(dir), (std::set<std::string>{"f_0.png", "f_1.png"}));
  EXPECT_TRUE(contains(r.output, "t 3.5 .. 4 s at 2 fps")) << r.output;
}

TEST(CliSequence, RefusesBadRangesAndPatternsBeforeWritingAnything) {
  const fs::path dir = scratch_dir("sequence-refusals");
  const std::string out = (dir / "frames" / "f_%04d.png").string();
  const std::string animated =
      std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-cornell.bounce.json";
  const struct {
    std::string args;
    std::string problem;
  } cases[] = {
      {"cornell --to 1 -o " + (dir / "frames" / "f.png").string(), "no conversion"},
      {"cornell --to 1 -o " + (dir / "frames" / "f_%d_%d.png").string(), "2 conversions"},
      {"cornell --to 1 -o " + (dir / "frames" / "f_%s.png").string(),
       "unsupported conversion '%s'"},
      {"cornell --to 1 -o " + (dir / "frames" / "f_%x.png").string(),
       "unsupported conversion '%x'"},
      {"cornell --to 1 -o " + (dir / "frames" / "f_%d.jpg").string(),
       "unsupported extension '.jpg'"},
      {"cornell --to 1 -o " + (dir / "%d" / "f.png").string(), "not in a directory"},
      {"cornell --from 2 --to 1 -o " + out, "--to 1 s is before --from 2 s"},
      {"cornell --from=-1 --to 1 -o " + out, "--from must be"},
      {"cornell --to nan -o " + out, "--to"},
      {"cornell --to inf -o " + out, "--to"},
      {"cornell --to 1 --fps 0 -o " + out, "--fps must be"},
      {"cornell --to 1 --fps 1001 -o " + out, "--fps must be"},
      {"cornell --to 1 --fps nan -o " + out, "--fps"},
      {"cornell --to 1 --every 0 -o " + out, "--every must be at least 1"},
      {"cornell --to 10000 --fps 30 -o " + out, "300001 frames; at most 100000"},
      {"cornell -o " + out, "no animation or camera path to take the length from: give --to"},
      {animated + " --from 5 -o " + out, "past the end of the animation (4 s)"},
      {(dir / "missing.bounce.json").string() + " --to 1 -o " + out, "missing.bounce.json"},
  };
  for (const auto& c : cases) {
    const Result r = run("sequence " + c.args + " -W 8 -H 8");
    EXPECT_NE(r.status, 0) << c.args << "\n" << r.output;
    EXPECT_NE(r.status, -1) << c.args << "\n" << r.output;  // an exit, not a crash
    EXPECT_TRUE(contains(r.output, c.problem)) << c.args << "\n" << r.output;
    EXPECT_TRUE(entries(dir).empty()) << c.args;
  }
  // The pattern is quoted in its refusal, and the message is the program's own.
  const Result r = run("sequence cornell --to 1 -o " + (dir / "f_%x.png").string());
  EXPECT_TRUE(contains(r.output, "bounce: error: -o '" + (dir / "f_%x.png").string() + "'"))
      << r.output;
}

// Limits the size of files the processes started here may write, and ignores the signal that
// would kill them, so writing past the limit fails with EFBIG like a full disk would.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
    previous_ = std::signal(SIGXFSZ, SIG_IGN);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_)(int) = SIG_DFL;
};

TEST(CliSequence, AFailedWriteLeavesNoPartialFile) {
  // A write that fails part-way: 64x64 linear EXR frames are far over a 2 KiB file size limit.
  const fs::path dir = scratch_dir("sequence-partial");
  Result r;
  {
    const FileSizeLimit limit(2048);
    r = run("sequence cornell -t direct -W 64 -H 64 --to 0.1 --fps 10 -o " +
            (dir / "f_%d.exr").string());
  }
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "bounce: error: cannot write " + (dir / "f_0.exr").string()))
      << r.output;
  EXPECT_TRUE(entries(dir).empty()) << "left behind: " << *entries(dir).begin();

  // A target that cannot be written (a directory of that name): the frames before it are
  // complete, no temporary is left, and the run stops with the name of the file.
  fs::create_directories(dir / "f_1.png");
  r = run("sequence cornell -t direct -W 16 -H 16 --to 0.2 --fps 10 -o " +
          (dir / "f_%d.png").string());
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "cannot write " + (dir / "f_1.png").string())) << r.output;
  EXPECT_EQ(entries(dir), (std::set<std::string>{"f_0.png", "f_1.png"}));
  EXPECT_EQ(load_image((dir / "f_0.png").string()).width(), 16);

  // A directory that cannot be created (a file is in the way).
  std::ofstream(dir / "file") << "x";
  r = run("sequence cornell -t direct -W 16 -H 16 --to 0.2 --fps 10 -o " +
          (dir / "file" / "f_%d.png").string());
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "cannot create the directory '" + (dir / "file").string()))
      << r.output;
}

// A Cornell box with a cube that moves between t = 0 and 1 s, seen from `camera`, and, when
// `path` is set, a camera path from pose A (t = 0) to pose B (t = 1). Nothing loops.
std::string scene_text(const std::string& camera, bool path) {
  const std::string cube = std::string(BOUNCE_SOURCE_DIR) + "/scenes/models/cube.obj";
  std::string text = R"({"models": [{"builtin": "cornell"},
    {"file": ")" + cube +
                     R"(", "translate": [0.15, 0.1, 0.1], "scale": 0.2,
     "animation": {"keys": [{"time": 0, "translate": [0.15, 0.1, 0.1]},
                            {"time": 1, "translate": [0.4, 0.1, 0.3]}]}}],
    "camera": )" + camera;
  if (path)
    text += R"(, "camera_path": {"keys": [
      {"time": 0, "position": [0.278, 0.273, -0.8], "look_at": [0.278, 0.273, 0]},
      {"time": 1, "position": [0.1, 0.4, -0.5], "look_at": [0.35, 0.2, 0.4]}]})";
  return text + R"(, "loop": false})";  // a loop would be back at t = 0 when t = 1
}

TEST(CliSequence, FramesFollowTheCameraPathAndTheAnimation) {
  const fs::path dir = scratch_dir("sequence-path");
  const std::string pose_a =
      R"({"position": [0.278, 0.273, -0.8], "look_at": [0.278, 0.273, 0], "fov_deg": 39.3077})";
  const std::string pose_b =
      R"({"position": [0.1, 0.4, -0.5], "look_at": [0.35, 0.2, 0.4], "fov_deg": 39.3077})";
  const std::string pose_c =
      R"({"position": [0.5, 0.1, -0.6], "look_at": [0.2, 0.3, 0.2], "fov_deg": 39.3077})";
  const auto write_scene = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  // The sequence's scene stands at pose C; its path goes from A to B.
  const std::string path_scene = write_scene("path.bounce.json", scene_text(pose_c, true));
  const std::string at_a = write_scene("a.bounce.json", scene_text(pose_a, false));
  const std::string at_b = write_scene("b.bounce.json", scene_text(pose_b, false));
  const std::string at_c = write_scene("c.bounce.json", scene_text(pose_c, false));
  // The raw pipeline: a first frame is then exactly render's (the denoiser jitters it).
  const std::string common = " -t direct --light-samples 16 -W 32 -H 32 --no-denoise";

  Result r = run("sequence " + path_scene + common + " --from 0 --to 1 --fps 1 -o " +
                 (dir / "seq_%d.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto render = [&](const std::string& scene, const std::string& at) {
    const std::string out =
        (dir / ("render-" + fs::path(scene).stem().string() + "-" + at + ".exr")).string();
    const Result rr = run("render " + scene + common + " --spp 1 --at " + at + " -o " + out);
    EXPECT_EQ(rr.status, 0) << rr.output;
    return load_image(out);
  };
  const Image first = load_image((dir / "seq_0.exr").string());
  const Image second = load_image((dir / "seq_1.exr").string());
  const Image a0 = render(at_a, "0"), b0 = render(at_b, "0"), b1 = render(at_b, "1");
  const Image c1 = render(at_c, "1");  // the scene's own camera, which the path overrides

  // Frame 0 is the path's pose A with the cube at its start: the same first frame as render.
  EXPECT_LT(mean_difference(first, a0), 1e-6 * mean_difference(b1, a0));
  // Frame 1 is pose B with the cube moved. It comes after a frame of history, so it matches a
  // fresh render up to noise, which is far below what the wrong pose or the unmoved cube shows.
  const double match = mean_difference(second, b1);
  EXPECT_LT(match, 0.2 * mean_difference(second, c1)) << match;
  EXPECT_LT(match, 0.2 * mean_difference(second, b0)) << match;
}

}  // namespace
}  // namespace bounce
