#include "report.h"

#include <fmt/format.h>

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

}  // namespace bounce::app
