// Report printing shared by the commands: per-stage timing tables, durations.
#pragma once

#include <string>

#include "bounce/core/timer.h"

namespace bounce::app {

void print_stage_table(const StageStatistics& stats, bool with_stddev);

// A duration for progress lines: "M:SS", or "H:MM:SS" from an hour on.
std::string clock_text(double seconds);

// A progress line on stderr: rewritten in place on a terminal; in a log, a new line only when
// the caller says one is due, so that logs stay short. Ends the line in place when destroyed.
class ProgressLine {
 public:
  ProgressLine();
  ~ProgressLine() { finish(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool terminal() const { return terminal_; }
  void show(const std::string& text, bool due_in_log);
  void finish();

 private:
  bool terminal_;
  bool dirty_ = false;  // a line rewritten in place is not ended yet
};

}  // namespace bounce::app
