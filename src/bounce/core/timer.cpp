#include "bounce/core/timer.h"

#include <cmath>

namespace bounce {

void StageTimes::add(const std::string& name, double ms) {
  for (auto& s : stages_)
    if (s.name == name) {
      s.ms += ms;
      return;
    }
  stages_.push_back({name, ms});
}

double StageTimes::total_ms() const {
  double total = 0.0;
  for (const auto& s : stages_)
    if (s.name.find('/') == std::string::npos) total += s.ms;
  return total;
}

double StageTimes::get(const std::string& name) const {
  for (const auto& s : stages_)
    if (s.name == name) return s.ms;
  return 0.0;
}

}  // namespace bounce

namespace bounce {

namespace {

StageStatistics::Row summarise(const std::string& name, const std::vector<double>& ms,
                               size_t frames) {
  StageStatistics::Row row{name, 0.0, 0.0};
  if (frames == 0) return row;
  // A stage missing from some frames counts as 0 ms there.
  double sum = 0.0;
  for (double v : ms) sum += v;
  row.mean_ms = sum / double(frames);
  double sq = 0.0;
  for (double v : ms) sq += (v - row.mean_ms) * (v - row.mean_ms);
  sq += double(frames - ms.size()) * row.mean_ms * row.mean_ms;
  row.stddev_ms = frames > 1 ? std::sqrt(sq / double(frames - 1)) : 0.0;
  return row;
}

}  // namespace

StageStatistics::Samples& StageStatistics::samples_for(const std::string& name) {
  for (auto& s : stages_)
    if (s.name == name) return s;
  stages_.push_back({name, {}});
  return stages_.back();
}

void StageStatistics::add(const StageTimes& frame) {
  for (const auto& s : frame.stages()) samples_for(s.name).ms.push_back(s.ms);
  totals_.push_back(frame.total_ms());
  ++frames_;
}

std::vector<StageStatistics::Row> StageStatistics::rows() const {
  std::vector<Row> rows;
  for (const auto& s : stages_) rows.push_back(summarise(s.name, s.ms, frames_));
  rows.push_back(summarise("total", totals_, frames_));
  return rows;
}

}  // namespace bounce
