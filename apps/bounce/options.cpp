#include "options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iterator>

#include "bounce/core/error.h"
#include "bounce/gpu/cuda_pipeline.h"
#include "bounce/render/params_file.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
#include "input_checks.h"

namespace bounce::app {

std::string scene_stem(const std::string& scene) {
  std::string stem = std::filesystem::path(scene).filename().string();
  for (const char* ext : {".bounce.json", ".json", ".obj", ".gltf", ".glb"})
    if (stem.size() > std::strlen(ext) && stem.ends_with(ext)) {
      stem.resize(stem.size() - std::strlen(ext));
      break;
    }
  for (char& c : stem)
    if (c == ':') c = '-';
  return stem;
}

Scene load_scene_at(const std::string& spec, float at) {
  Scene scene = load_scene(spec);
  animate(scene, at);  // nothing to do for a still scene
  // A posed scene is seen from its camera path's camera at that time, when it has a path, so
  // that render, reference and sequence agree on the view at time t.
  scene.camera = scene.animation.camera_at(scene.camera, at);
  return scene;
}

FlashlightSettings flashlight_settings(const FrameOptions& options) {
  FlashlightSettings s;
  s.intensity *= options.flashlight_intensity / max_component(s.intensity);  // same colour
  return s;
}

std::optional<size_t> add_flashlight_option(const FrameOptions& options, Scene& scene) {
  if (!options.flashlight) return std::nullopt;
  return add_flashlight(scene, scene.camera, flashlight_settings(options));
}

FrameSettings FrameOptions::settings() const {
  FrameSettings s;
  s.width = width;
  s.height = height;
  s.light_samples = light_samples;
  s.one_shadow_ray = shadow_rays == "one" || (shadow_rays == "auto" && light_samples == 1);
  s.exposure_ev = exposure_ev;
  s.seed = seed;
  s.denoise = denoise;
  s.raster_primary = !trace_primary;
  s.moving_lights_apart = !moving_lights_in_history;
  return s;
}

namespace {
// The name in "name=value".
std::string assigned_name(const std::string& assignment) {
  return assignment.substr(0, assignment.find('='));
}
// Whether a --param assignment is the denoiser's: a name it has and the technique has not.
bool is_denoiser_param(const std::string& assignment, const ParamSet& technique) {
  static const Denoiser defaults;
  const std::string name = assigned_name(assignment);
  return defaults.params().find(name) != nullptr && technique.find(name) == nullptr;
}
}  // namespace

DenoiseSettings FrameOptions::denoise_settings() const {
  const auto owner = make_technique(technique);
  Denoiser denoiser;
  try {
    for (const auto& assignment : params)
      if (is_denoiser_param(assignment, owner->params()))
        denoiser.params().set_assignment(assignment);
  } catch (const Error& e) {
    fail("denoiser: {}", e.what());
  }
  return denoiser.settings();
}

void configure_pipeline(const FrameOptions& options, Renderer& renderer) {
  renderer.denoiser().settings() = options.denoise_settings();
  if (options.device == "cuda") renderer.set_device(make_cuda_pipeline());
}

FrameOptions realtime_frame_options() {
  FrameOptions o;
  o.light_samples = 1;
  return o;
}

FrameSettings realtime_frame_settings(const FrameOptions& options, bool moving) {
  FrameSettings s = options.settings();
  s.accumulate = true;
  // Jittered frames average into an antialiased image: at rest, and in motion too when the
  // denoiser's history follows surfaces (temporal antialiasing).
  s.jitter = s.denoise || !moving;
  return s;
}

void add_frame_options(CLI::App& command, FrameOptions& o, bool scene_required) {
  auto* scene = command.add_option(
      "scene", o.scene,
      "Scene: cornell, cubes:N[:SEED], leak, or a .obj, .gltf, .glb or .bounce.json file");
  if (scene_required)
    scene->required();
  else
    scene->capture_default_str();
  std::string techniques;
  for (const auto& n : technique_names()) techniques += (techniques.empty() ? "" : ", ") + n;
  command.add_option("-t,--technique", o.technique, "Indirect-light technique: " + techniques)
      ->capture_default_str();
  command.add_option("-W,--width", o.width, "Image width in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  command.add_option("-H,--height", o.height, "Image height in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  command
      .add_option("--light-samples", o.light_samples,
                  "Stratified samples per area light per pixel per frame")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  command
      .add_option("--shadow-rays", o.shadow_rays,
                  "Shadow rays per pixel: all (one per light sample), one (for all its light "
                  "samples, chosen by their unshadowed light: noise only where the lights' "
                  "shadows differ), or auto (one when --light-samples is 1)")
      ->check(CLI::IsMember(
          std::vector<std::string>(std::begin(kShadowRayChoices), std::end(kShadowRayChoices))))
      ->capture_default_str();
  command.add_option("--exposure", o.exposure_ev, "Exposure in stops for PNG output")
      ->check(CLI::Range(-kMaxExposureEv, kMaxExposureEv))
      ->capture_default_str();
  command.add_option("--seed", o.seed, "Seed of the sample patterns")->capture_default_str();
  command.add_flag("--trace-primary", o.trace_primary,
                   "Find each pixel's surface with a traced primary ray instead of rasterising "
                   "the triangles, which the renderer does where it pays (16 or more pixels a "
                   "triangle); the same surfaces up to rounding, for comparison");
  command.add_flag("--moving-lights-in-history", o.moving_lights_in_history,
                   "Average the light of moving point and spot lights (a carried flashlight) "
                   "into the denoiser's history like the rest, instead of shading them apart "
                   "with a shadow ray each and adding them after the denoiser; for comparison");
  command.add_option("--at", o.at, "Animated scenes: the animation time to pose the scene at, s")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  command.add_option("-j,--threads", o.threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  // Each technique's own options; a flag two techniques declare is added once.
  std::map<std::string, std::string> declared_by;
  std::map<std::string, std::string> help;
  for (const auto& name : technique_names())
    for (const TechniqueOption& option : make_technique(name)->options()) {
      std::string& who = declared_by[option.flag];
      who += (who.empty() ? "" : ", ") + name;
      if (!help.count(option.flag)) help[option.flag] = option.help;
    }
  for (const auto& [flag, techniques] : declared_by)
    command.add_option("--" + flag, o.technique_options[flag],
                       fmt::format("{} (technique {})", help[flag], techniques));
  command.add_option("-p,--param", o.params,
                     "Technique or denoiser parameter NAME=VALUE (repeatable; listed below)");
  // Added after --param, so CLI11 runs this callback after filling o.params: the file's
  // assignments go first and --param overrides them.
  command.add_option_function<std::string>(
      "--params",
      [&o](const std::string& file) {
        const std::vector<std::string> from_file = read_params_file(file);
        o.params.insert(o.params.begin(), from_file.begin(), from_file.end());
      },
      "JSON file of parameters {\"NAME\": VALUE, ...}; --param overrides it");
  command.add_flag("--flashlight", o.flashlight,
                   "The camera carries a spot light (the viewer's flashlight, key F) that follows "
                   "it along a camera path");
  command
      .add_option("--flashlight-intensity", o.flashlight_intensity,
                  "The flashlight's intensity on its axis, W/sr (a Quake level wants hundreds to a "
                  "thousand)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  command.add_flag("!--no-denoise", o.denoise,
                   "Show the raw pipeline: no temporal reuse or denoising");
  command
      .add_option("--device", o.device,
                  "Where the frame's stages run: cpu, or cuda (an NVIDIA GPU; techniques direct "
                  "and tiled)")
      ->check(CLI::IsMember({"cpu", "cuda"}))
      ->capture_default_str();
  command.footer(technique_parameters_help());
}

namespace {
// "--a, --b": a technique's option flags, for help and error messages.
std::string flag_list(const std::vector<TechniqueOption>& options) {
  std::string flags;
  for (const TechniqueOption& option : options)
    flags += (flags.empty() ? "" : ", ") + ("--" + option.flag);
  return flags;
}
}  // namespace

std::string technique_parameters_help() {
  std::string text = "Technique parameters (--param NAME=VALUE):\n";
  for (const auto& name : technique_names()) {
    const auto technique = make_technique(name);
    const std::string flags = flag_list(technique->options());
    if (!flags.empty()) text += fmt::format("  {} options: {}\n", name, flags);
    const auto& params = technique->params().all();
    if (params.empty()) text += "  " + name + ": none\n";
    for (const auto& p : params)
      text += fmt::format("  {}: {} = {} [{}, {}]  {}\n", name, p.name, p.to_string(), p.min, p.max,
                          p.help);
  }
  text += "Denoiser parameters (--param NAME=VALUE; every technique):\n";
  const Denoiser denoiser;
  for (const auto& p : denoiser.params().all())
    text += fmt::format("  {} = {} [{}, {}]  {}\n", p.name, p.to_string(), p.min, p.max, p.help);
  return text;
}

namespace {
void apply_parameters(const FrameOptions& o, Technique& technique);
}  // namespace

std::unique_ptr<Technique> make_configured_technique(const FrameOptions& o) {
  auto technique = make_technique(o.technique);
  try {
    apply_parameters(o, *technique);
  } catch (const Error& e) {
    fail("technique '{}': {}", o.technique, e.what());
  }
  return technique;
}

std::unique_ptr<Technique> make_checked_technique(const FrameOptions& o, const Scene& scene) {
  auto technique = make_configured_technique(o);
  check_memory(scene, o.width, o.height, kFrameBytesPerPixel, technique->memory_estimate(scene));
  return technique;
}

namespace {
void apply_parameters(const FrameOptions& o, Technique& technique) {
  ParamSet& params = technique.params();
  if (o.still)
    for (const auto& assignment : technique.still_defaults()) params.set_assignment(assignment);
  const std::vector<TechniqueOption> declared = technique.options();
  for (const auto& option : o.technique_options) {
    // Named copies, not a structured binding: clang 14 cannot capture one in the lambda.
    const std::string& flag = option.first;
    const std::string& text = option.second;
    if (text.empty()) continue;
    const auto it = std::find_if(declared.begin(), declared.end(),
                                 [&](const TechniqueOption& d) { return d.flag == flag; });
    if (it == declared.end()) {
      const std::string own = flag_list(declared);
      fail("--{} is not an option of this technique (its options: {})", flag,
           own.empty() ? "none" : own);
    }
    it->apply(params, text);
  }
  for (const auto& assignment : o.params)
    if (!is_denoiser_param(assignment, params)) params.set_assignment(assignment);
}
}  // namespace

}  // namespace bounce::app
