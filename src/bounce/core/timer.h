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
// Kept as running moments (Welford), so memory stays constant however many frames are added:
// a soak of 10,000 frames must not grow by the samples it has seen.
class StageStatistics {
 public:
  struct Row {
    std::string name;
    double mean_ms = 0.0;
    double stddev_ms = 0.0;
  };
  void add(const StageTimes& frame);
  size_t frames() const { return frames_; }
  // One row per stage in pipeline order, then "total". A stage missing from some frames counts
  // as 0 ms there.
  std::vector<Row> rows() const;

  // Running count, mean and sum of squared deviations of the values added.
  struct Moments {
    size_t n = 0;
    double mean = 0.0, m2 = 0.0;
    void add(double v);
  };

 private:
  struct Stage {
    std::string name;
    Moments ms;  // over the frames the stage appeared in
  };
  Stage& stage_for(const std::string& name);
  std::vector<Stage> stages_;
  Moments totals_;
  size_t frames_ = 0;
};

}  // namespace bounce
