#include "options.h"

#include <fmt/format.h>

#include "bounce/render/technique.h"

namespace bounce::app {

FrameSettings FrameOptions::settings() const {
  FrameSettings s;
  s.width = width;
  s.height = height;
  s.light_samples = light_samples;
  s.exposure_ev = exposure_ev;
  s.seed = seed;
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
  command.add_option("--exposure", o.exposure_ev, "Exposure in stops for PNG output")
      ->capture_default_str();
  command.add_option("--seed", o.seed, "Seed of the sample patterns")->capture_default_str();
  command.add_option("-j,--threads", o.threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  command.add_option("-p,--param", o.params,
                     "Technique parameter NAME=VALUE (repeatable; listed below)");
  command.footer(technique_parameters_help());
}

std::string technique_parameters_help() {
  std::string text = "Technique parameters (--param NAME=VALUE):\n";
  for (const auto& name : technique_names()) {
    const auto technique = make_technique(name);
    const auto& params = technique->params().all();
    if (params.empty()) text += "  " + name + ": none\n";
    for (const auto& p : params)
      text += fmt::format("  {}: {} = {} [{}, {}]  {}\n", name, p.name, p.to_string(), p.min, p.max,
                          p.help);
  }
  return text;
}

std::unique_ptr<Technique> make_configured_technique(const FrameOptions& o) {
  auto technique = make_technique(o.technique);
  for (const auto& assignment : o.params) technique->params().set_assignment(assignment);
  return technique;
}

}  // namespace bounce::app
