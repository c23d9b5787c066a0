// Printing of per-stage timing tables, shared by the commands.
#pragma once

#include "bounce/core/timer.h"

namespace bounce::app {

void print_stage_table(const StageStatistics& stats, bool with_stddev);

}  // namespace bounce::app
