// bench --json: a machine-readable record of a benchmark run (timings, throughput, build, machine).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bounce/core/resident_memory.h"
#include "bounce/core/timer.h"
#include "bounce/eval/temporal_runs.h"
#include "bounce/render/renderer.h"

namespace bounce::app {

// bench --flicker / --settle (bounce/eval/temporal_runs.h).
struct TemporalRecord {
  int width = 0, height = 0;  // the size the temporal runs rendered at
  int flicker_frames = 0;     // 0: flicker not measured
  int flicker_warmup = 0;
  double flicker_at_rest = 0.0, flicker_accumulation_off = 0.0;
  bool settle = false;  // false: settle not measured
  SettleOptions settle_options;
  SettleResult settle_result;
};

struct BenchRecord {
  std::string scene;
  std::string technique;
  std::vector<std::pair<std::string, std::string>> params;  // the technique's, name and value
  FrameSettings settings;
  int frames = 0;
  int warmup = 0;
  int threads = 0;
  const StageStatistics* stats = nullptr;
  // Totals over the timed frames.
  double primary_rays = 0.0, shadow_rays = 0.0, technique_rays = 0.0;
  double photon_paths = 0.0, photons_stored = 0.0, photons_reused = 0.0;
  double gbuffer_ms = 0.0, direct_ms = 0.0;
  double technique_ms = 0.0;                 // the technique's stages: prepare and indirect
  const TemporalRecord* temporal = nullptr;  // "flicker" and "settle" (null when not measured)
  const MemorySamples* memory = nullptr;     // "resident_memory" (null when not sampled)
  double memory_growth = 0.0;                // peak after warm-up / first after warm-up - 1
};

// Writes the record as JSON to `path`, atomically (a temporary file renamed over the target).
void write_bench_json(const std::string& path, const BenchRecord& record);

}  // namespace bounce::app
