// bounce sequence: an animation or camera path rendered as the viewer shows it, frame after frame
// through one Renderer (all temporal state kept) at a fixed rate, the displayed frames written as
// numbered images. This is how quality in motion is measured and walkthrough videos are made.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/core/interrupt.h"
#include "bounce/core/parallel.h"
#include "bounce/scene/load.h"
#include "frame_pattern.h"
#include "frame_range.h"
#include "input_checks.h"
#include "options.h"
#include "report.h"

namespace bounce::app {

namespace {

struct SequenceOptions {
  FrameOptions frame = realtime_frame_options();
  double fps = 30.0;
  double from = 0.0, to = 0.0;  // seconds
  bool from_given = false;      // else --at (or 0)
  bool to_given = false;        // else the animation's duration
  int every = 1;
  int64_t warmup = 0;           // frames rendered before --from, not written
  bool global_numbers = false;  // file numbers count from 0 s, not from --from
  std::string out;              // frame pattern; empty: default_pattern()
  std::string json;             // --json: per-frame record
};

std::string default_pattern(const std::string& scene) {
  std::string stem;
  for (char c : scene_stem(scene)) stem += c == '%' ? std::string("%%") : std::string(1, c);
  return "out/sequence/" + stem + "_%04d.png";
}

void create_directory(const FramePattern& pattern) {
  if (pattern.directory().empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(pattern.directory(), ec);
  if (ec || !std::filesystem::is_directory(pattern.directory()))
    fail("-o '{}': cannot create the directory '{}': {}", pattern.pattern(), pattern.directory(),
         ec ? ec.message() : "a file of that name is in the way");
}

void run_sequence(const SequenceOptions& o) {
  install_interrupt_handlers();  // this command polls for them (throw_if_interrupted)
  const ThreadLimit limit(o.frame.threads);
  // Everything that can be refused is checked before the first frame renders.
  const FramePattern pattern(o.out.empty() ? default_pattern(o.frame.scene) : o.out);
  const double from = o.from_given ? o.from : double(o.frame.at);
  if (!std::isfinite(from) || from < 0.0)  // checked again in make_frame_range; the pose needs it
    fail("--from must be a finite time of at least 0 s, got {}", from);
  Scene scene = load_scene_at(o.frame.scene, float(from));
  const bool animated = !scene.animation.empty() || !scene.animation.camera_path.empty();
  double to = 0.0;
  if (o.to_given) {
    to = o.to;
  } else {
    if (!animated || scene.animation.duration() <= 0.0f)
      fail("{}: the scene has no animation or camera path to take the length from: give --to",
           scene.source);
    to = scene.animation.duration();
    if (to < from)
      fail("--from {:g} s is past the end of the animation ({:g} s); give --to", from, to);
  }
  const FrameRange range = make_frame_range(from, to, o.fps, o.every, o.warmup);
  if (o.global_numbers && range.origin < 0)
    fail(
        "--global-numbers: --from {:g} s is not on the frame grid at {:g} fps (a whole number of "
        "frames from 0 s)",
        from, o.fps);
  const std::optional<size_t> flashlight = add_flashlight_option(o.frame, scene);
  auto technique = make_checked_technique(o.frame, scene);
  create_directory(pattern);

  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, std::move(technique));
  configure_pipeline(o.frame, renderer);
  // Frame numbers seed the samples: a range that starts part way numbers its frames as a run
  // from 0 s would, warm-up included.
  if (range.origin >= 0) renderer.set_frame_index(uint32_t(range.number(-range.warmup)));
  StageStatistics stats;
  nlohmann::json frames = nlohmann::json::array();
  double frame_ms_sum = 0.0;
  double first_frame_ms = 0.0;  // the first timed frame: it also sizes the pipeline's buffers
  int64_t written = 0;
  const Stopwatch wall;
  {
    // Progress: in place on a terminal; in a log at most once a second, and a last line only
    // after an earlier one (a short run needs none).
    ProgressLine progress;
    double printed_s = 0.0;
    for (int64_t k = -range.warmup; k < range.count; ++k) {
      throw_if_interrupted();  // frames written so far stay; none is written half-way
      const double t = range.time(k);
      if (!scene.animation.empty()) renderer.animate(scene, float(t));
      const Camera camera = scene.animation.camera_at(scene.camera, float(t));
      if (flashlight &&
          place_flashlight(scene, *flashlight, camera, flashlight_settings(o.frame))) {
        SceneChange moved;
        moved.lights = true;
        renderer.scene_changed(moved);
      }
      const bool moving =
          renderer.next_change(camera, realtime_frame_settings(o.frame, true)).any();
      const Frame& frame = renderer.render(camera, realtime_frame_settings(o.frame, moving));
      if (k < 0) continue;  // warm-up: state only, neither written nor timed
      stats.add(frame.times);
      const double frame_ms = frame.times.total_ms();
      frame_ms_sum += frame_ms;
      if (k == 0) first_frame_ms = frame_ms;
      nlohmann::json record = {{"index", k}, {"time", t}, {"ms", frame_ms}};
      const int64_t number = o.global_numbers ? range.number(k) : k;
      if (number % range.every == 0) {
        const std::string name = pattern.name(number);
        save_image(name, frame.color, o.frame.exposure_ev);
        record["file"] = name;
        ++written;
      }
      if (!o.json.empty()) {
        nlohmann::json stages = nlohmann::json::object();
        for (const StageTime& s : frame.times.stages()) stages[s.name] = s.ms;
        record["stages"] = std::move(stages);
        frames.push_back(std::move(record));
      }
      const int64_t done = k + 1;
      const double elapsed_s = wall.elapsed_ms() / 1000.0;
      const bool due = done == range.count ? printed_s > 0.0 : elapsed_s - printed_s >= 1.0;
      if (due) printed_s = elapsed_s;
      const double per_frame_s = elapsed_s / double(done);
      progress.show(
          fmt::format("sequence: frame {}/{} (t {:.3f} s), {:.1f} ms per frame, elapsed {}, ETA {}",
                      done, range.count, t, 1000.0 * per_frame_s, clock_text(elapsed_s),
                      clock_text(per_frame_s * double(range.count - done))),
          due);
    }
  }
  const double wall_ms = wall.elapsed_ms();
  const double mean_ms = frame_ms_sum / double(range.count);
  // Without a warm-up the first frame also allocates and fills what later frames reuse (bench
  // leaves it out the same way): the mean of the others is what a walk shows once it runs.
  const bool after_first = range.warmup == 0 && range.count > 1;
  const double later_mean_ms =
      after_first ? (frame_ms_sum - first_frame_ms) / double(range.count - 1) : mean_ms;

  const FrameSettings settings = realtime_frame_settings(o.frame, true);
  fmt::print("sequence {} technique {} {}x{}, {} light samples, t {:g} .. {:g} s at {:g} fps\n",
             scene.source, renderer.technique().name(), settings.width, settings.height,
             settings.light_samples, range.from, range.to, range.fps);
  print_stage_table(stats, true);
  if (range.warmup > 0) fmt::print("{} warm-up frames before {:g} s\n", range.warmup, range.from);
  fmt::print("{} frames rendered, {} written{}: {}\n", range.count, written,
             range.every > 1 ? fmt::format(" (every {})", range.every) : "", pattern.pattern());
  fmt::print("mean frame {:.2f} ms ({:.1f} fps); {:.2f} ms per frame with writing\n", mean_ms,
             mean_ms > 0.0 ? 1000.0 / mean_ms : 0.0, wall_ms / double(range.count));
  if (after_first)
    fmt::print("mean frame after the first {:.2f} ms ({:.1f} fps); the first {:.2f} ms\n",
               later_mean_ms, later_mean_ms > 0.0 ? 1000.0 / later_mean_ms : 0.0, first_frame_ms);
  if (o.json.empty()) return;
  nlohmann::json j = {{"scene", scene.source},
                      {"technique", renderer.technique().name()},
                      {"width", settings.width},
                      {"height", settings.height},
                      {"light_samples", settings.light_samples},
                      {"shadow_rays", settings.one_shadow_ray ? "one" : "all"},
                      {"moving_lights", settings.moving_lights_apart ? "apart" : "history"},
                      {"from", range.from},
                      {"to", range.to},
                      {"fps", range.fps},
                      {"every", range.every},
                      {"warmup", range.warmup},
                      {"global_numbers", o.global_numbers},
                      {"pattern", pattern.pattern()},
                      {"frames_rendered", range.count},
                      {"frames_written", written},
                      {"mean_frame_ms", mean_ms},
                      {"mean_frame_ms_after_first", later_mean_ms},
                      {"frames", std::move(frames)}};
  for (const Param& p : renderer.technique().params().all()) j["params"][p.name] = p.to_string();
  const std::filesystem::path parent = std::filesystem::path(o.json).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  save_text_file(o.json, j.dump(2) + "\n");
  fmt::print("wrote {}\n", o.json);
}

}  // namespace

void add_sequence_command(CLI::App& app) {
  auto o = std::make_shared<SequenceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sequence",
      "Render an animation or camera path as the viewer shows it (real-time frames with their "
      "temporal state) at a fixed rate, and write the frames");
  add_frame_options(*cmd, o->frame, true);
  cmd->add_option("--fps", o->fps, "Frames per second of animation time")->capture_default_str();
  cmd->add_option("--from", o->from, "Start time, s (default: --at, else 0)");
  cmd->add_option("--to", o->to,
                  "End time, s, included when a frame falls on it (default: the length of the "
                  "scene's animation and camera path; required for a scene without)");
  cmd->add_option("--every", o->every,
                  "Write every Nth frame (k % N == 0); all frames are still rendered")
      ->capture_default_str();
  cmd->add_option("--warmup", o->warmup,
                  "Frames rendered before --from and not written, to rebuild the temporal state a "
                  "run from 0 s would have there (cut to the frames after 0 s)")
      ->check(CLI::Range(int64_t(0), kMaxSequenceFrames))
      ->capture_default_str();
  cmd->add_flag("--global-numbers", o->global_numbers,
                "Number the files by the frame's index from 0 s (time x fps) instead of from "
                "--from, and keep --every frames by that number: ranges rendered apart then "
                "write one sequence of files");
  cmd->add_option("-o,--out", o->out,
                  "Frame files: a pattern with one integer conversion for the frame number k "
                  "(at time from + k/fps), ending in .png (tone-mapped), .exr or .pfm (linear); "
                  "default out/sequence/SCENE_%04d.png")
      ->check(non_empty_path());
  cmd->add_option("--json", o->json, "Also write per-frame times and file names as JSON here")
      ->check(non_empty_path());
  cmd->callback([o, cmd] {
    o->from_given = cmd->count("--from") > 0;
    o->to_given = cmd->count("--to") > 0;
    run_sequence(*o);
  });
}

}  // namespace bounce::app
