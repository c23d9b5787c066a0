// bounce render: one image of a scene to PNG (tone-mapped), EXR or PFM (linear).
#include <fmt/format.h>

#include <cstring>
#include <filesystem>

#include "bounce/core/image_io.h"
#include "bounce/core/parallel.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
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

// A still image affords more photons per pass than a real-time frame: unless told otherwise,
// photon techniques trace kStillPhotons paths per pass here (bench keeps their own default).
constexpr const char* kStillPhotons = "20000";

std::unique_ptr<Technique> make_still_technique(FrameOptions o) {
  if (o.photons.empty() && make_technique(o.technique)->params().find("photons"))
    o.photons = kStillPhotons;
  return make_configured_technique(o);
}

void run_render(const RenderOptions& o) {
  const ThreadLimit limit(o.frame.threads);
  const std::string out = o.out.empty() ? default_output(o.frame.scene) : o.out;
  Stopwatch load_watch;
  const Scene scene = load_scene_at(o.frame.scene, o.frame.at);
  const double load_ms = load_watch.elapsed_ms();
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_still_technique(o.frame));
  FrameSettings settings = o.frame.settings();
  settings.jitter = o.spp > 1;

  StageStatistics stats;
  Image sum(settings.width, settings.height);
  uint64_t primary = 0, shadow = 0;
  for (int k = 0; k < o.spp; ++k) {
    const Frame& frame = renderer.render(scene.camera, settings);
    sum += frame.color;
    stats.add(frame.times);
    primary += frame.primary_rays;
    shadow += frame.shadow_rays;
  }
  const Image image = sum * (1.0f / float(o.spp));

  fmt::print(
      "{}: {} triangles, {} lights + {} area lights; loaded in {:.1f} ms, BVH built in "
      "{:.1f} ms\n",
      scene.source, scene.triangle_count(), scene.lights.size(), scene.area_lights.size(), load_ms,
      tracer->stats().build_ms);
  fmt::print("technique {}, {}x{}, {} frame(s) averaged, {} light samples per frame\n",
             renderer.technique().name(), settings.width, settings.height, o.spp,
             settings.light_samples);
  print_stage_table(stats, false);
  fmt::print("rays: {} primary, {} shadow\n", primary, shadow);

  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
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
                  "Output file: .png (tone-mapped), .exr or .pfm (linear); default out/SCENE.png");
  cmd->callback([options] { run_render(*options); });
}

}  // namespace bounce::app
