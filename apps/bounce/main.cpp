// bounce: real-time global illumination by photon mapping. The command-line entry point.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <exception>

#include "bounce/core/error.h"
#include "bounce/core/interrupt.h"
#include "input_checks.h"
#include "options.h"

int main(int argc, char** argv) {
  CLI::App app{"bounce: real-time global illumination by photon mapping"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every command");
  bounce::app::add_render_command(app);
  bounce::app::add_info_command(app);
  bounce::app::add_bench_command(app);
  bounce::app::add_reference_command(app);
  bounce::app::add_compare_command(app);
  bounce::app::add_view_command(app);
  bounce::app::add_sequence_command(app);
  bounce::app::add_merge_command(app);
  bounce::app::refuse_non_finite_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with status 0: CLI11 prints them.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    fmt::print(stderr, "bounce: error: {}\n", e.what());
    fmt::print(stderr, "Run with --help for more information.\n");
    return 1;
  } catch (const bounce::Interrupted& e) {
    fmt::print(stderr, "bounce: {}\n", e.what());
    return 128 + e.signal();  // the shell's status for a process ended by that signal
  } catch (const bounce::Error& e) {
    fmt::print(stderr, "bounce: error: {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "bounce: internal error: {}\n", e.what());
    return 2;
  }
  return 0;
}
