// Report printing shared by the commands: per-stage timing tables, durations.
#pragma once

#include <string>

#include "bounce/core/timer.h"

namespace bounce::app {

void print_stage_table(const StageStatistics& stats, bool with_stddev);

// A duration for progress lines: "M:SS", or "H:MM:SS" from an hour on.
std::string clock_text(double seconds);

}  // namespace bounce::app
