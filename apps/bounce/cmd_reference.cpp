// bounce reference: a converged path-traced image (the ground truth), with progress and ETA.
#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/core/interrupt.h"
#include "bounce/core/parallel.h"
#include "bounce/core/timer.h"
#include "bounce/interactive/flashlight.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/path/reference_slices.h"
#include "input_checks.h"
#include "options.h"
#include "report.h"

namespace bounce::app {

namespace {

struct ReferenceOptions {
  std::string scene = "cornell";
  int width = 256;
  int height = 256;
  int spp = 1024;
  int sample_offset = 0;  // first sample of a slice (bounce merge combines slices)
  double time_s = 0.0;
  int max_bounces = -1;
  int rr_start = 3;
  int light_candidates = PathSettings().light_candidates;
  uint32_t seed = 0;
  int threads = 0;
  float exposure_ev = 0.0f;
  float at = 0.0f;  // animation time
  bool flashlight = false;
  float flashlight_intensity = 3.0f;  // W/sr
  std::string out;
  std::string checkpoint;          // resume from and save to this file (empty: none)
  double checkpoint_every_s = 60;  // seconds between checkpoint saves
};

std::string default_output(const std::string& scene) {
  return "out/" + scene_stem(scene) + "-reference.exr";
}

void run_reference(const ReferenceOptions& o) {
  install_interrupt_handlers();  // this command polls for them (throw_if_interrupted)
  const ThreadLimit limit(o.threads);
  const std::string out = o.out.empty() ? default_output(o.scene) : o.out;
  check_output_image(out);  // now, not after minutes of rendering
  Scene scene = load_scene_at(o.scene, o.at);
  if (o.flashlight) {
    FrameOptions frame;  // the flashlight of render and sequence at this intensity
    frame.flashlight_intensity = o.flashlight_intensity;
    add_flashlight(scene, scene.camera, flashlight_settings(frame));
  }
  auto tracer = make_embree_tracer(scene);
  ReferenceSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.spp = o.spp;
  settings.first_sample = o.sample_offset;
  settings.time_limit_s = o.time_s;
  settings.seed = o.seed;
  settings.path.max_bounces = o.max_bounces;
  settings.path.rr_start = o.rr_start;
  settings.path.light_candidates = o.light_candidates;

  check_memory(scene, o.width, o.height, kReferenceBytesPerPixel);

  // A checkpoint resumes the samples of an earlier run with the same key, and is saved every
  // checkpoint_every_s seconds and when the run is interrupted.
  ReferenceState state;
  const ReferenceCheckpointKey key{
      fmt::format("{} at {}{}", o.scene, o.at,
                  o.flashlight ? fmt::format(" with flashlight {}", o.flashlight_intensity) : ""),
      o.width,
      o.height,
      o.seed,
      o.max_bounces,
      o.rr_start,
      o.sample_offset,
      o.light_candidates};
  if (!o.checkpoint.empty() && std::filesystem::exists(o.checkpoint)) {
    state = load_reference_checkpoint(o.checkpoint, key);
    fmt::print("resuming {} from {} spp\n", o.checkpoint, state.spp);
  }
  Stopwatch since_save;
  const auto save_checkpoint = [&] {
    save_reference_checkpoint(o.checkpoint, key, state);
    since_save = Stopwatch();
  };

  // Progress: in place on a terminal, every 10% in a log.
  ProgressLine line;
  int last_tenth = -1;
  const auto progress = [&](const ReferenceProgress& p) {
    if (!o.checkpoint.empty() &&
        (interrupt_signal() != 0 || since_save.elapsed_ms() >= 1e3 * o.checkpoint_every_s)) {
      save_checkpoint();
      if (interrupt_signal() != 0)
        warn(fmt::format("saved {} spp to {}: run the same command to resume", state.spp,
                         o.checkpoint));
    }
    throw_if_interrupted();  // between passes: the partial image is dropped
    const int percent = int(std::floor(100.0 * p.fraction));
    const bool due = percent / 10 > last_tenth;
    if (due) last_tenth = percent / 10;
    line.show(fmt::format("reference: {:3}% ({}/{} spp), elapsed {}, ETA {}", percent, p.spp_done,
                          p.spp_target, clock_text(p.elapsed_s), clock_text(p.eta_s)),
              due);
  };
  const ReferenceResult r =
      render_reference(scene, *tracer, scene.camera, settings, progress, &state);
  line.finish();
  throw_if_interrupted();
  // An EXR records what it holds (scene, settings, sample range), so bounce merge can combine
  // slices and refuse ones that do not belong together.
  if (lower_case_extension(out) == ".exr")
    save_exr(out, r.image, reference_attributes(key, r.spp));
  else
    save_image(out, r.image, o.exposure_ev);
  if (!o.checkpoint.empty()) save_checkpoint();  // a later run with more --spp goes on from here
  const std::string bounces =
      o.max_bounces < 0 ? std::string("unlimited") : fmt::format("{}", o.max_bounces);
  fmt::print("reference {} {}x{}: {} spp, max bounces {}, seed {}\n", scene.source, o.width,
             o.height, r.spp, bounces, o.seed);
  if (o.sample_offset > 0)
    fmt::print("samples {} .. {} of each pixel's sequence\n", o.sample_offset,
               int64_t(o.sample_offset) + r.spp - 1);
  fmt::print("time {:.1f} s, {:.1f} M rays ({:.2f} M rays/s)\n", r.seconds, r.rays * 1e-6,
             r.seconds > 0.0 ? r.rays * 1e-6 / r.seconds : 0.0);
  if (r.nonfinite > 0) warn(fmt::format("{} non-finite samples were dropped", r.nonfinite));
  fmt::print("wrote {}\n", out);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reference", "Path-trace a converged reference image (no SCENE: the Cornell box)");
  cmd->add_option("scene", o->scene,
                  "Scene: cornell, cubes:N[:SEED], leak, or a .obj, .gltf, .glb or .bounce.json "
                  "file")
      ->capture_default_str();
  cmd->add_option("-W,--width", o->width, "Image width in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  cmd->add_option("-H,--height", o->height, "Image height in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  cmd->add_option("--spp", o->spp, "Samples (paths) per pixel")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  cmd->add_option("--sample-offset", o->sample_offset,
                  "Index of the first sample: the run takes samples K .. K+spp-1 of the sequence "
                  "a single run takes, a slice that bounce merge combines with the others")
      ->check(CLI::Range(0, kMaxReferenceSample - (1 << 24)))
      ->capture_default_str();
  cmd->add_option("--time", o->time_s,
                  "Stop after this many seconds even if --spp is not reached (0: no limit)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  cmd->add_option("--at", o->at, "Animated scenes: the animation time to pose the scene at, s")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  cmd->add_flag("--flashlight", o->flashlight,
                "The camera carries the viewer's flashlight (as render --flashlight)");
  cmd->add_option("--flashlight-intensity", o->flashlight_intensity,
                  "The flashlight's intensity on its axis, W/sr")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  cmd->add_option("--max-bounces", o->max_bounces,
                  "Indirect bounces counted: 0 direct light only, 1 one bounce, ...; -1 no limit")
      ->check(CLI::Range(-1, 1024))
      ->capture_default_str();
  cmd->add_option("--rr-start", o->rr_start,
                  "Path vertex from which Russian roulette may end paths")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_option("--light-candidates", o->light_candidates,
                  fmt::format("Scenes with more than {} lights: light samples drawn by power per "
                              "next-event estimate, one kept by its unshadowed contribution (with "
                              "fewer lights a sample of each; 1: one light drawn by power)",
                              PathSettings().resample_above_lights))
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the paths' random numbers")->capture_default_str();
  cmd->add_option("-j,--threads", o->threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_option("--exposure", o->exposure_ev, "Exposure in stops for PNG output")
      ->check(CLI::Range(-kMaxExposureEv, kMaxExposureEv))
      ->capture_default_str();
  cmd->add_option("--checkpoint", o->checkpoint,
                  "Save the samples to this file as the run goes (and when interrupted); when it "
                  "exists, resume from it: the result equals an uninterrupted run")
      ->check(non_empty_path());
  cmd->add_option("--checkpoint-every", o->checkpoint_every_s, "Seconds between checkpoint saves")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  cmd->add_option("-o,--out", o->out,
                  "Output: .exr or .pfm (linear), .png (tone-mapped); default "
                  "out/SCENE-reference.exr")
      ->check(non_empty_path());
  cmd->callback([o] { run_reference(*o); });
}

}  // namespace bounce::app
