// Options shared by the commands that render frames (render, bench, ...).
#pragma once

#include <CLI/CLI.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bounce/interactive/flashlight.h"
#include "bounce/render/renderer.h"

namespace bounce::app {

// The values of --shadow-rays (FrameOptions::shadow_rays), for the CLI and the viewer's panel.
inline constexpr const char* kShadowRayChoices[] = {"auto", "all", "one"};

struct FrameOptions {
  std::string scene = "cornell";
  std::string technique = "tiled";
  int width = 512;
  int height = 512;
  int light_samples = 16;
  // --shadow-rays: "all" (one per light sample), "one" (one per pixel for all its samples,
  // chosen by unshadowed contribution) or "auto" (one with a single light sample per light).
  std::string shadow_rays = "auto";
  float exposure_ev = 0.0f;
  uint32_t seed = 0;
  int threads = 0;
  float at = 0.0f;  // animation time the scene is posed at, seconds
  std::vector<std::string> params;
  // The options techniques declare (Technique::options()), by flag: the text given, or empty.
  std::map<std::string, std::string> technique_options;
  // A still image: the technique's still_defaults() apply before the user's options.
  bool still = false;
  bool denoise = true;         // temporal reuse and denoising (--no-denoise: the raw pipeline)
  std::string device = "cpu";  // where the frame's stages run: cpu or cuda
  bool flashlight = false;     // --flashlight: the camera carries the viewer's spot light
  // Its intensity on the axis, W/sr (the viewer's 3 suits a room of metres; levels tens of
  // metres across need hundreds to a thousand).
  float flashlight_intensity = 3.0f;
  bool trace_primary = false;  // --trace-primary: a traced ray per pixel, not the raster
  // --moving-lights-in-history: moved lights' light averaged with the rest (for comparison)
  bool moving_lights_in_history = false;

  FrameSettings settings() const;
  // The denoiser's parameters: its defaults and the --param assignments that name them.
  DenoiseSettings denoise_settings() const;
};

// Frame options of the real-time commands (view, bench, sequence): one area-light sample per
// pixel per frame, since frames average at rest or are seen only for a moment in motion.
FrameOptions realtime_frame_options();
// One real-time frame as the viewer shows it: history and accumulation at rest on; sub-pixel
// jitter at rest, and in motion too when denoising (the history follows surfaces, so jittered
// frames average into an antialiased image either way).
FrameSettings realtime_frame_settings(const FrameOptions& options, bool moving);

// Adds [SCENE] and the frame options to a command.
void add_frame_options(CLI::App& command, FrameOptions& options, bool scene_required);
// Loads a scene and, if it is animated, poses it at `at` seconds (its camera too, when it has a
// camera path).
Scene load_scene_at(const std::string& spec, float at);
// The flashlight of the options: the viewer's, at --flashlight-intensity.
FlashlightSettings flashlight_settings(const FrameOptions& options);
// With --flashlight, adds the flashlight at the scene's camera to its lights (before the renderer
// is made) and returns its index there, for place_flashlight as the camera moves; else nullopt.
std::optional<size_t> add_flashlight_option(const FrameOptions& options, Scene& scene);
// A file-name stem for a scene spec: "cubes:100" -> "cubes-100", "dir/room.obj" -> "room".
std::string scene_stem(const std::string& scene);

// Lists every technique's options and parameters with their defaults and ranges (for --help).
std::string technique_parameters_help();
// Applies the pipeline's own parameters (the denoiser's) and the --device to a renderer (fails
// clearly when --device cuda cannot run here).
void configure_pipeline(const FrameOptions& options, Renderer& renderer);
// Creates the technique and applies its still defaults (for a still), its options and the --param
// assignments, in that order (throws Error on a bad one, or an option of another technique).
std::unique_ptr<Technique> make_configured_technique(const FrameOptions& options);
// The configured technique, after checking that a frame pipeline of the options' size with the
// data that technique keeps fits under the memory cap (check_memory; throws Error when not).
std::unique_ptr<Technique> make_checked_technique(const FrameOptions& options, const Scene& scene);

// Command registration: each command lives in its own file.
void add_render_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_sequence_command(CLI::App& app);
void add_merge_command(CLI::App& app);

}  // namespace bounce::app
