// bounce bench: many frames of a scene; mean and standard deviation per stage after warm-up;
// --flicker and --settle add the temporal metrics (bounce/eval/temporal_runs.h).
#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "bench_json.h"
#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/resident_memory.h"
#include "bounce/core/timer.h"
#include "bounce/eval/temporal_runs.h"
#include "bounce/scene/load.h"
#include "input_checks.h"
#include "options.h"
#include "report.h"

namespace bounce::app {

namespace {

struct BenchOptions {
  // Real-time frames: one light sample per pixel per frame unless asked otherwise.
  BenchOptions() : frame(realtime_frame_options()) {}
  FrameOptions frame;
  int frames = 100;
  int warmup = 10;
  std::string json;  // --json: also write a machine-readable record here
  // Temporal metrics (temporal_runs.h), at kTemporalSize unless -W/-H were given.
  int flicker = 0;  // frames measured for flicker; 0: off
  bool settle = false;
  SettleOptions settle_options;
  bool width_given = false, height_given = false;
  bool animate = false;  // play the scene's animation, 1/30 s per frame
  // Frames at rest average into a converged image (as the viewer at rest); off, every frame is
  // a real-time frame as in motion.
  bool accumulate = false;
  int memory_every = 0;  // --memory-every: sample resident memory every K frames; 0: off
};

constexpr float kAnimationStep = 1.0f / 30.0f;

// Image size of the temporal runs unless -W/-H say otherwise: they render hundreds of frames.
constexpr int kTemporalSize = 128;

// Flicker and settle runs; prints them and fills the JSON record's part.
TemporalRecord run_temporal(const BenchOptions& o, const Scene& scene) {
  TemporalRecord t;
  FrameSettings settings = o.frame.settings();
  settings.width = o.width_given ? o.frame.width : kTemporalSize;
  settings.height = o.height_given ? o.frame.height : kTemporalSize;
  t.width = settings.width;
  t.height = settings.height;
  const TechniqueFactory make = [&o] { return make_configured_technique(o.frame); };
  const DenoiseSettings denoise = o.frame.denoise_settings();
  if (o.flicker > 0) {
    t.flicker_frames = o.flicker;
    t.flicker_warmup = o.warmup;
    t.flicker_at_rest =
        measure_flicker(scene, make, settings, o.warmup, o.flicker, true, denoise).flicker;
    const FlickerResult off =
        measure_flicker(scene, make, settings, o.warmup, o.flicker, false, denoise);
    t.flicker_accumulation_off = off.flicker;
    fmt::print(
        "flicker ({}x{}, {} frames after {} warm-up): {:.4f} at rest, {:.4f} with accumulation "
        "off (FrameSettings.accumulate=false)\n",
        t.width, t.height, o.flicker, o.warmup, t.flicker_at_rest, t.flicker_accumulation_off);
  }
  if (o.settle) {
    t.settle = true;
    t.settle_options = o.settle_options;
    t.settle_result = measure_settle(scene, make, settings, o.settle_options, denoise);
    const SettleResult& r = t.settle_result;
    const SettleOptions& so = o.settle_options;
    const std::string where =
        fmt::format("{}x{}, {}-pixel blocks, target: mean indirect of frames {}..{} after the move",
                    t.width, t.height, so.block, so.frames, so.frames + so.target_frames - 1);
    if (!r.applicable)
      fmt::print("settle: n/a ({})\n", r.reason);
    else if (r.settle_frame == kNotSettled)
      fmt::print("settle ({}): not within {:g}% after {} frames; last error {:.1f}%\n", where,
                 100.0 * so.tolerance, so.frames, 100.0 * r.errors.back());
    else
      fmt::print("settle ({}): {} frames to within {:g}%; first frame's error {:.1f}%\n", where,
                 r.settle_frame, 100.0 * so.tolerance, 100.0 * r.errors.front());
    if (r.applicable)
      fmt::print(
          "  light '{}' moved by {:g} of the scene diagonal ({:.3g}, {:.3g}, {:.3g}); before the "
          "move the converged indirect light was {:.1f}% off\n",
          r.light, so.move_fraction, r.offset.x, r.offset.y, r.offset.z, 100.0 * r.change);
  }
  return t;
}

void run_bench(BenchOptions o) {
  const ThreadLimit limit(o.frame.threads);
  const Stopwatch load_watch;
  Scene scene = load_scene_at(o.frame.scene, o.frame.at);
  const double load_ms = load_watch.elapsed_ms();
  if (o.animate && scene.animation.empty())
    fail("{}: --animate: the scene has no animation", scene.source);
  add_flashlight_option(o.frame, scene);  // the camera stays where it is: placed once
  auto technique = make_checked_technique(o.frame, scene);
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, std::move(technique));
  configure_pipeline(o.frame, renderer);
  FrameSettings settings = o.frame.settings();
  settings.accumulate = o.accumulate;
  settings.host_color = false;  // a frame's work ends with the displayed (tone-mapped) image
  int frame_number = 0;
  MemorySamples memory;
  const auto next_frame = [&]() -> const Frame& {
    if (o.animate) renderer.animate(scene, o.frame.at + kAnimationStep * float(frame_number));
    ++frame_number;
    const Frame& f = renderer.render(scene.camera, settings);
    if (o.memory_every > 0 && frame_number % o.memory_every == 0)
      memory.add(frame_number, resident_memory_bytes());
    return f;
  };

  // The first frame builds what later frames reuse (photon maps, refined meshes, hit buffers):
  // reported apart, since the warm-up hides it from the table.
  double first_ms = 0.0, first_prepare_ms = 0.0;
  for (int k = 0; k < o.warmup; ++k) {
    const Frame& f = next_frame();
    if (k == 0) first_ms = f.times.total_ms(), first_prepare_ms = f.times.get("prepare");
  }
  StageStatistics stats;
  double primary = 0.0, shadow = 0.0, gbuffer_ms = 0.0, direct_ms = 0.0;
  BenchRecord record;
  for (int k = 0; k < o.frames; ++k) {
    const Frame& f = next_frame();
    if (k == 0 && o.warmup == 0)
      first_ms = f.times.total_ms(), first_prepare_ms = f.times.get("prepare");
    stats.add(f.times);
    primary += double(f.primary_rays);
    shadow += double(f.shadow_rays);
    gbuffer_ms += f.times.get("gbuffer");
    direct_ms += f.times.get("direct");
    // A technique's time: its prepare and indirect stages (none for one without indirect light).
    if (renderer.technique().has_indirect())
      record.technique_ms += f.times.get("prepare") + f.times.get("indirect");
    record.technique_rays += double(f.technique.rays);
    record.photon_paths += double(f.technique.photon_paths);
    record.photons_stored += double(f.technique.photons_stored);
    record.photons_reused += double(f.technique.photons_reused);
  }
  const int threads =
      o.frame.threads > 0 ? o.frame.threads : int(std::thread::hardware_concurrency());
  fmt::print(
      "bench {} technique {} {}x{}, {} light samples, {} frames after {} warm-up, {} "
      "threads{}{}\n",
      scene.source, renderer.technique().name(), settings.width, settings.height,
      settings.light_samples, o.frames, o.warmup, threads, o.animate ? ", animated" : "",
      o.accumulate ? ", accumulating at rest" : "");
  fmt::print("scene loaded in {:.1f} ms, {} triangles; BVH built in {:.1f} ms\n", load_ms,
             scene.triangle_count(), tracer->stats().build_ms);
  print_stage_table(stats, true);
  const double total_ms = stats.rows().back().mean_ms;
  fmt::print("frame rate                   {:>10.1f} fps\n",
             total_ms > 0 ? 1000.0 / total_ms : 0.0);
  fmt::print("primary rays/s (gbuffer)     {:>10.2f} M\n", primary / (gbuffer_ms * 1e3));
  fmt::print("shadow rays/s (direct stage) {:>10.2f} M  ({:.0f} shadow rays per frame)\n",
             shadow / (direct_ms * 1e3), shadow / o.frames);
  if (record.photons_stored > 0)
    fmt::print(
        "photons per frame            {:>10.0f}    ({:.0f} paths traced, {:.0f} photons of "
        "unchanged paths kept; {:.2f} M traced and stored/s)\n",
        record.photons_stored / o.frames, record.photon_paths / o.frames,
        record.photons_reused / o.frames,
        (record.photons_stored - record.photons_reused) /
            (stats.rows().back().mean_ms * o.frames * 1e3));
  // The estimate is what the memory check before the first frame allowed for: exact for
  // buffers sized up front (lhb), an upper bound where photon counts vary (vertex), so the
  // process's resident memory is printed beside it.
  if (const uint64_t kept = renderer.technique().memory_estimate(scene); kept > 0)
    fmt::print(
        "technique data (bound)       {:>10.1f} MiB  (the most its photons, meshes and buffers "
        "can take)\n",
        double(kept) / (1024.0 * 1024.0));
  if (o.memory_every == 0)
    if (const uint64_t resident = resident_memory_bytes(); resident > 0)
      fmt::print(
          "resident memory              {:>10.1f} MiB  (the whole process, after the last "
          "frame)\n",
          double(resident) / (1024.0 * 1024.0));
  fmt::print(
      "first frame                  {:>10.1f} ms  (prepare {:.1f} ms: what later frames reuse)\n",
      first_ms, first_prepare_ms);
  if (o.memory_every > 0 && !memory.frames.empty()) {
    record.memory = &memory;
    record.memory_growth = memory.growth_after(o.warmup);
    const auto first = std::lower_bound(memory.frames.begin(), memory.frames.end(), o.warmup);
    const size_t i0 = first == memory.frames.end() ? 0 : size_t(first - memory.frames.begin());
    const auto peak = *std::max_element(memory.bytes.begin() + long(i0), memory.bytes.end());
    fmt::print(
        "resident memory              {:>10.1f} MiB after warm-up, {:.1f} at the end, peak "
        "{:.1f} ({:+.2f}%; {} samples, every {} frames)\n",
        double(memory.bytes[i0]) / 1048576.0, double(memory.bytes.back()) / 1048576.0,
        double(peak) / 1048576.0, 100.0 * record.memory_growth, memory.frames.size(),
        o.memory_every);
  }
  TemporalRecord temporal;
  if (o.flicker > 0 || o.settle) temporal = run_temporal(o, scene);
  if (o.json.empty()) return;
  record.temporal = &temporal;
  record.scene = scene.source;
  record.technique = renderer.technique().name();
  for (const auto& p : renderer.technique().params().all())
    record.params.emplace_back(p.name, p.to_string());
  record.settings = settings;
  record.frames = o.frames;
  record.warmup = o.warmup;
  record.threads = threads;
  record.stats = &stats;
  record.primary_rays = primary;
  record.shadow_rays = shadow;
  record.gbuffer_ms = gbuffer_ms;
  record.direct_ms = direct_ms;
  write_bench_json(o.json, record);
  fmt::print("wrote {}\n", o.json);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Time many frames: mean and deviation per stage");
  add_frame_options(*cmd, options->frame, true);
  cmd->add_option("-n,--frames", options->frames, "Frames timed after warm-up")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--warmup", options->warmup, "Frames rendered before timing")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_flag("--animate", options->animate,
                "Play the scene's animation (1/30 s per frame): the scene stage then shows the "
                "cost of posing the scene and refitting the acceleration structure");
  cmd->add_flag("--accumulate", options->accumulate,
                "Average frames at rest into a converged image, as the viewer does at rest "
                "(default: every frame is a real-time frame, as in motion)");
  cmd->add_option("--memory-every", options->memory_every,
                  "Sample the process's resident memory every K frames (warm-up included); prints "
                  "its growth after warm-up and writes the samples to --json")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--json", options->json,
                  "Also write the results, build and machine as JSON to this file")
      ->check(non_empty_path());
  const std::string size = fmt::format("{0}x{0} unless -W/-H are given", kTemporalSize);
  cmd->add_option(
         "--flicker", options->flicker,
         "Also measure flicker over N frames at rest, and with accumulation off (" + size + ")")
      ->check(CLI::Range(0, 1000000));
  cmd->add_flag("--settle", options->settle,
                "Also count the frames indirect light needs to settle within the tolerance after "
                "the first light moves (" +
                    size + ")");
  cmd->add_option("--settle-frames", options->settle_options.frames,
                  "Settle: frames measured after the move (the cap); as many are rendered at "
                  "rest before it, and 4 times as many after them for the converged target")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--settle-tolerance", options->settle_options.tolerance,
                  "Settle: relative L1 error of block sums counted as settled")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--settle-block", options->settle_options.block,
                  "Settle: side of the pixel blocks whose sums are compared")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  cmd->callback([options, cmd] {
    options->width_given = cmd->count("--width") > 0;
    options->height_given = cmd->count("--height") > 0;
    SettleOptions& s = options->settle_options;
    s.rest_frames = s.frames;
    s.target_frames = 4 * s.frames;
    run_bench(*options);
  });
}

}  // namespace bounce::app
