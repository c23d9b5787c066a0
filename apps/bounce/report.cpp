#include "report.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bounce::app {

void print_stage_table(const StageStatistics& stats, bool with_stddev) {
  fmt::print("{:<28} {:>10}{}\n", "stage", "mean ms", with_stddev ? "   stddev ms" : "");
  for (const auto& row : stats.rows()) {
    if (with_stddev)
      fmt::print("{:<28} {:>10.3f} {:>11.3f}\n", row.name, row.mean_ms, row.stddev_ms);
    else
      fmt::print("{:<28} {:>10.3f}\n", row.name, row.mean_ms);
  }
}

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

ProgressLine::ProgressLine() : terminal_(isatty(fileno(stderr)) != 0) {}

void ProgressLine::show(const std::string& text, bool due_in_log) {
  if (terminal_) {
    fmt::print(stderr, "\r{:<80}", text);
    std::fflush(stderr);
    dirty_ = true;
  } else if (due_in_log) {
    fmt::print(stderr, "{}\n", text);
  }
}

void ProgressLine::finish() {
  if (dirty_) fmt::print(stderr, "\n");
  dirty_ = false;
}

}  // namespace bounce::app
