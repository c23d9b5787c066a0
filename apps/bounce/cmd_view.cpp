// bounce view: the interactive viewer (apps/bounce/view/), and its headless, scripted form.
#include "bounce/core/error.h"
#include "input_checks.h"
#include "options.h"
#include "view/script.h"
#include "view/view_window.h"

namespace bounce::app {

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<ViewOptions>();
  options->frame = realtime_frame_options();  // frames average at rest
  options->frame.width = 960;
  options->frame.height = 540;
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Interactive viewer (no SCENE: the Cornell box). Keys: WASD move, Q/E down/up, shift "
      "faster, mouse drag look, wheel speed, F flashlight, space play animation, C camera path, "
      "P screenshot, Tab panel, Esc quit");
  add_frame_options(*cmd, options->frame, false);
  cmd->add_option("--frames", options->frames, "Stop after N frames (0: run until closed)")
      ->check(CLI::Range(0, 1 << 30));
  cmd->add_option("--screenshot", options->screenshot,
                  "Save the window as PNG after the last frame")
      ->check(non_empty_path());
  cmd->add_option("--script", options->script, "Play scripted actions (below), then stop")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--hide-ui", options->hide_ui, "Start with the panel hidden (Tab shows it)");
  cmd->add_option("--target-ms", options->target_ms,
                  "Frame-time goal in motion: the internal resolution scales to hold it (0: off)")
      ->check(CLI::Range(0.0, 10000.0))
      ->capture_default_str();
  cmd->footer(script_help() + "\n" + technique_parameters_help());
  cmd->callback([options] {
    if (options->screenshot.size() > 0 && !options->screenshot.ends_with(".png"))
      fail("--screenshot: '{}' must be a .png file", options->screenshot);
    run_viewer(*options);
  });
}

}  // namespace bounce::app
