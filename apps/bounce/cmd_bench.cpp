// bounce bench: many frames of a scene; mean and standard deviation per stage after warm-up.
#include <fmt/format.h>

#include <thread>

#include "bench_json.h"
#include "bounce/core/parallel.h"
#include "bounce/scene/load.h"
#include "options.h"
#include "report.h"

namespace bounce::app {

namespace {

struct BenchOptions {
  // Real-time frames: one light sample per pixel per frame unless asked otherwise.
  BenchOptions() { frame.light_samples = 1; }
  FrameOptions frame;
  int frames = 100;
  int warmup = 10;
  std::string json;  // --json: also write a machine-readable record here
};

void run_bench(BenchOptions o) {
  const ThreadLimit limit(o.frame.threads);
  const Scene scene = load_scene(o.frame.scene);
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_configured_technique(o.frame));
  const FrameSettings settings = o.frame.settings();

  for (int k = 0; k < o.warmup; ++k) renderer.render(scene.camera, settings);
  StageStatistics stats;
  double primary = 0.0, shadow = 0.0, gbuffer_ms = 0.0, direct_ms = 0.0;
  BenchRecord record;
  for (int k = 0; k < o.frames; ++k) {
    const Frame& f = renderer.render(scene.camera, settings);
    stats.add(f.times);
    primary += double(f.primary_rays);
    shadow += double(f.shadow_rays);
    gbuffer_ms += f.times.get("gbuffer");
    direct_ms += f.times.get("direct");
    record.indirect_ms += f.times.get("indirect");
    record.technique_rays += double(f.technique.rays);
    record.photon_paths += double(f.technique.photon_paths);
    record.photons_stored += double(f.technique.photons_stored);
  }
  const int threads =
      o.frame.threads > 0 ? o.frame.threads : int(std::thread::hardware_concurrency());
  fmt::print(
      "bench {} technique {} {}x{}, {} light samples, {} frames after {} warm-up, {} "
      "threads\n",
      scene.source, renderer.technique().name(), settings.width, settings.height,
      settings.light_samples, o.frames, o.warmup, threads);
  print_stage_table(stats, true);
  const double total_ms = stats.rows().back().mean_ms;
  fmt::print("frame rate                   {:>10.1f} fps\n",
             total_ms > 0 ? 1000.0 / total_ms : 0.0);
  fmt::print("primary rays/s (gbuffer)     {:>10.2f} M\n", primary / (gbuffer_ms * 1e3));
  fmt::print("shadow rays/s (direct stage) {:>10.2f} M  ({:.0f} shadow rays per frame)\n",
             shadow / (direct_ms * 1e3), shadow / o.frames);
  if (o.json.empty()) return;
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
  cmd->add_option("--json", options->json,
                  "Also write the results, build and machine as JSON to this file");
  cmd->callback([options] { run_bench(*options); });
}

}  // namespace bounce::app
