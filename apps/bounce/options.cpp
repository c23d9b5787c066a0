#include "options.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "bounce/core/error.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

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
  return scene;
}

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
  command.add_option("--at", o.at, "Animated scenes: the animation time to pose the scene at, s")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  command.add_option("-j,--threads", o.threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  command.add_option("--photons", o.photons,
                     "Photon paths per frame (photon techniques; render: 20000 unless given)");
  command.add_option("--radius", o.radius,
                     "Gather radius: scene units (0.05) or percent of the scene diagonal (3%)");
  command.add_option("--bounces", o.bounces,
                     "Photon bounces: -1 = until Russian roulette ends the path, 1 = the seed's");
  command.add_option("--lowres", o.lowres, "Indirect light at 1/N of the width and height");
  command.add_option("--tile", o.tile, "Screen tile size in pixels (tile gather)");
  command.add_option("--gather", o.gather, "Density estimation: tiles or grid")
      ->check(CLI::IsMember({"tiles", "grid"}));
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

namespace {
void apply_parameters(const FrameOptions& o, ParamSet& params);
}  // namespace

std::unique_ptr<Technique> make_configured_technique(const FrameOptions& o) {
  auto technique = make_technique(o.technique);
  try {
    apply_parameters(o, technique->params());
  } catch (const Error& e) {
    fail("technique '{}': {}", o.technique, e.what());
  }
  return technique;
}

namespace {
void apply_parameters(const FrameOptions& o, ParamSet& params) {
  const auto shortcut = [&](const std::string& value, const std::string& name) {
    if (!value.empty()) params.set(name, value);
  };
  shortcut(o.photons, "photons");
  shortcut(o.bounces, "bounces");
  shortcut(o.lowres, "lowres");
  shortcut(o.tile, "tile");
  if (!o.gather.empty()) params.set("gather", o.gather == "tiles" ? "0" : "1");
  if (!o.radius.empty()) {
    if (o.radius.back() == '%') {
      // Percent of the diagonal, as the relative radius; "0" turns the absolute one off.
      const std::string number = o.radius.substr(0, o.radius.size() - 1);
      char* end = nullptr;
      const double percent = std::strtod(number.c_str(), &end);
      if (number.empty() || *end != '\0') fail("--radius: '{}' is not a percentage", o.radius);
      params.set("radius_rel", fmt::format("{}", percent / 100.0));
      params.set("radius", "0");
    } else {
      params.set("radius", o.radius);
    }
  }
  for (const auto& assignment : o.params) params.set_assignment(assignment);
}
}  // namespace

}  // namespace bounce::app
