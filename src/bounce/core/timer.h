// Per-stage frame timing: every stage of the frame pipeline is recorded under its own name.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace bounce {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

struct StageTime {
  std::string name;
  double ms = 0.0;
};

// The stage times of one frame, in pipeline order. A stage added twice accumulates.
class StageTimes {
 public:
  void add(const std::string& name, double ms);
  double total_ms() const;  // sums top-level stages; "indirect/..." sub-stages are inside them
  double get(const std::string& name) const;  // 0 when absent
  const std::vector<StageTime>& stages() const { return stages_; }
  void clear() { stages_.clear(); }

 private:
  std::vector<StageTime> stages_;
};

// Times the enclosing scope as stage `name`.
class ScopedStage {
 public:
  ScopedStage(StageTimes& times, std::string name) : times_(times), name_(std::move(name)) {}
  ~ScopedStage() { times_.add(name_, watch_.elapsed_ms()); }
  ScopedStage(const ScopedStage&) = delete;
  ScopedStage& operator=(const ScopedStage&) = delete;

 private:
  StageTimes& times_;
  std::string name_;
  Stopwatch watch_;
};

}  // namespace bounce

namespace bounce {

// Statistics of stage times over many frames: mean and sample standard deviation per stage.
class StageStatistics {
 public:
  struct Row {
    std::string name;
    double mean_ms = 0.0;
    double stddev_ms = 0.0;
  };
  void add(const StageTimes& frame);
  size_t frames() const { return frames_; }
  // One row per stage in pipeline order, then "total".
  std::vector<Row> rows() const;

 private:
  struct Samples {
    std::string name;
    std::vector<double> ms;
  };
  Samples& samples_for(const std::string& name);
  std::vector<Samples> stages_;
  std::vector<double> totals_;
  size_t frames_ = 0;
};

}  // namespace bounce
