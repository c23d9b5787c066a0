// bounce render: one image of a scene to PNG (tone-mapped), EXR or PFM (linear).
#include <fmt/format.h>

#include <cstring>
#include <filesystem>

#include "bounce/core/image_io.h"
#include "bounce/core/interrupt.h"
#include "bounce/core/parallel.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
#include "input_checks.h"
#include "options.h"
#include "report.h"

namespace bounce::app {

namespace {

struct RenderOptions {
  FrameOptions frame;
  int spp = 16;
  std::string out;
};

std::string default_output(const std::string& scene) {
  return "out/" + scene_stem(scene) + ".png";
}

void run_render(const RenderOptions& o) {
  install_interrupt_handlers();  // this command polls for them (throw_if_interrupted)
  const ThreadLimit limit(o.frame.threads);
  const std::string out = o.out.empty() ? default_output(o.frame.scene) : o.out;
  check_output_image(out);  // now, not after the render
  Stopwatch load_watch;
  Scene scene = load_scene_at(o.frame.scene, o.frame.at);
  const double load_ms = load_watch.elapsed_ms();
  add_flashlight_option(o.frame, scene);  // a still: placed once at the camera
  FrameOptions frame_options = o.frame;
  frame_options.still = true;  // a still affords more work per pass than a real-time frame
  auto technique = make_checked_technique(frame_options, scene);
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, std::move(technique));
  configure_pipeline(frame_options, renderer);
  FrameSettings settings = o.frame.settings();
  // The passes are frames at rest: the pipeline averages them (techniques that accumulate
  // themselves, like tiled's shrinking-radius passes, are not averaged again).
  settings.jitter = o.spp > 1;
  settings.accumulate = true;

  StageStatistics stats;
  uint64_t primary = 0, shadow = 0;
  const Frame* frame = nullptr;
  for (int k = 0; k < o.spp; ++k) {
    throw_if_interrupted();
    frame = &renderer.render(scene.camera, settings);
    stats.add(frame->times);
    primary += frame->primary_rays;
    shadow += frame->shadow_rays;
  }
  const Image& image = frame->color;

  fmt::print(
      "{}: {} triangles, {} lights + {} area lights; loaded in {:.1f} ms, BVH built in "
      "{:.1f} ms\n",
      scene.source, scene.triangle_count(), scene.lights.size(), scene.area_lights.size(), load_ms,
      tracer->stats().build_ms);
  fmt::print("technique {}, {}x{}, {} frame(s) averaged, {} light samples per frame\n",
             renderer.technique().name(), settings.width, settings.height, o.spp,
             settings.light_samples);
  std::string params;
  for (const Param& p : renderer.technique().params().all())
    params += fmt::format("{}{}={}", params.empty() ? "" : " ", p.name, p.to_string());
  if (!params.empty()) fmt::print("parameters: {}\n", params);
  if (settings.denoise) {
    std::string denoiser;
    for (const Param& p : renderer.denoiser().params().all())
      denoiser += fmt::format("{}{}={}", denoiser.empty() ? "" : " ", p.name, p.to_string());
    fmt::print("denoiser: {}\n", denoiser);
  } else {
    fmt::print("denoiser: off\n");
  }
  print_stage_table(stats, false);
  fmt::print("rays: {} primary, {} shadow\n", primary, shadow);

  throw_if_interrupted();
  save_image(out, image, settings.exposure_ev);
  fmt::print("wrote {}\n", out);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render one image (no SCENE: the Cornell box)");
  add_frame_options(*cmd, options->frame, false);
  cmd->add_option("--spp", options->spp,
                  "Jittered frames averaged into the image (samples per pixel)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option("-o,--out", options->out,
                  "Output file: .png (tone-mapped), .exr or .pfm (linear); default out/SCENE.png")
      ->check(non_empty_path());
  cmd->callback([options] { run_render(*options); });
}

}  // namespace bounce::app
