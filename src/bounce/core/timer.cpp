#include "bounce/core/timer.h"

#include <algorithm>
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

// Mean and sample standard deviation over `frames` frames, of which moments.n had the stage and
// the rest count as 0 ms: the two groups combine as in Chan et al.'s pairwise update (1979).
StageStatistics::Row summarise(const std::string& name, const StageStatistics::Moments& m,
                               size_t frames) {
  StageStatistics::Row row{name, 0.0, 0.0};
  if (frames == 0) return row;
  const double n = double(m.n), total = double(frames);
  row.mean_ms = m.mean * n / total;
  const double m2 = m.m2 + m.mean * m.mean * n * (total - n) / total;
  row.stddev_ms = frames > 1 ? std::sqrt(std::max(m2, 0.0) / (total - 1.0)) : 0.0;
  return row;
}

}  // namespace

void StageStatistics::Moments::add(double v) {
  ++n;
  const double delta = v - mean;
  mean += delta / double(n);
  m2 += delta * (v - mean);
}

StageStatistics::Stage& StageStatistics::stage_for(const std::string& name) {
  for (auto& s : stages_)
    if (s.name == name) return s;
  stages_.push_back({name, {}});
  return stages_.back();
}

void StageStatistics::add(const StageTimes& frame) {
  for (const auto& s : frame.stages()) stage_for(s.name).ms.add(s.ms);
  totals_.add(frame.total_ms());
  ++frames_;
}

std::vector<StageStatistics::Row> StageStatistics::rows() const {
  std::vector<Row> rows;
  for (const auto& s : stages_) rows.push_back(summarise(s.name, s.ms, frames_));
  rows.push_back(summarise("total", totals_, frames_));
  return rows;
}

}  // namespace bounce
