#include "bench_json.h"

#include <nlohmann/json.hpp>

#include "bounce/core/image_io.h"
#include "build_info.h"

namespace bounce::app {

namespace {

// Events per second over a total time in ms; null when nothing was timed.
nlohmann::json per_second(double count, double ms) {
  return ms > 0.0 ? nlohmann::json(count / (ms * 1e-3)) : nlohmann::json();
}

}  // namespace

void write_bench_json(const std::string& path, const BenchRecord& r) {
  using nlohmann::json;
  json stages = json::array();
  json total;
  for (const auto& row : r.stats->rows()) {
    const json entry = {{"name", row.name}, {"mean_ms", row.mean_ms}, {"stddev_ms", row.stddev_ms}};
    if (row.name == "total")
      total = entry;
    else
      stages.push_back(entry);
  }
  json params = json::object();
  for (const auto& [name, value] : r.params) params[name] = value;
  const BuildInfo build = build_info();
  const MachineInfo machine = machine_info();
  const double frames = r.frames > 0 ? double(r.frames) : 1.0;
  const double mean_ms = total.is_null() ? 0.0 : total["mean_ms"].get<double>();

  const json record = {
      {"bounce_version", build.version},
      {"build",
       {{"compiler", build.compiler},
        {"build_type", build.build_type},
        {"git_revision_at_configure", build.git_revision}}},
      {"machine",
       {{"cpu", machine.cpu}, {"logical_cores", machine.logical_cores}, {"threads", r.threads}}},
      {"scene", r.scene},
      {"technique", r.technique},
      {"params", params},
      {"width", r.settings.width},
      {"height", r.settings.height},
      {"light_samples", r.settings.light_samples},
      {"seed", r.settings.seed},
      {"frames", r.frames},
      {"warmup_frames", r.warmup},
      {"stages", stages},
      {"total", total},
      {"fps", mean_ms > 0.0 ? json(1000.0 / mean_ms) : json()},
      {"rays",
       {{"primary_per_frame", r.primary_rays / frames},
        {"shadow_per_frame", r.shadow_rays / frames},
        {"technique_per_frame", r.technique_rays / frames},
        // Each kind over the time of the stage that traces it.
        {"primary_per_s", per_second(r.primary_rays, r.gbuffer_ms)},
        {"shadow_per_s", per_second(r.shadow_rays, r.direct_ms)},
        {"technique_per_s", per_second(r.technique_rays, r.indirect_ms)}}},
      {"photons",
       {{"paths_per_frame", r.photon_paths / frames},
        {"stored_per_frame", r.photons_stored / frames},
        // Photon paths over the whole indirect stage's time (tracing plus estimation).
        {"paths_per_s", per_second(r.photon_paths, r.indirect_ms)}}},
  };
  save_text_file(path, record.dump(2) + "\n");
}

}  // namespace bounce::app
