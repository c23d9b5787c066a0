#include "bench_json.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "bounce/core/image_io.h"
#include "build_info.h"

namespace bounce::app {

namespace {

// Events per second over a total time in ms; null when nothing was timed.
nlohmann::json per_second(double count, double ms) {
  return ms > 0.0 ? nlohmann::json(count / (ms * 1e-3)) : nlohmann::json();
}

// A number, or null when it is not finite (JSON has no NaN or infinity).
nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

nlohmann::json flicker_json(const TemporalRecord* t) {
  if (!t || t->flicker_frames <= 0) return nullptr;
  return {{"width", t->width},
          {"height", t->height},
          {"frames", t->flicker_frames},
          {"warmup_frames", t->flicker_warmup},
          {"at_rest", finite_or_null(t->flicker_at_rest)},
          {"accumulation_off", finite_or_null(t->flicker_accumulation_off)}};
}

nlohmann::json settle_json(const TemporalRecord* t) {
  using nlohmann::json;
  if (!t || !t->settle) return nullptr;
  const SettleOptions& o = t->settle_options;
  const SettleResult& r = t->settle_result;
  json errors = json::array();
  for (const double e : r.errors) errors.push_back(finite_or_null(e));
  const bool settled = r.applicable && r.settle_frame != kNotSettled;
  return {{"width", t->width},
          {"height", t->height},
          {"applicable", r.applicable},
          {"reason", r.reason},
          {"frames", settled ? json(r.settle_frame) : json()},
          {"settled", settled},
          {"max_frames", o.frames},
          {"rest_frames", o.rest_frames},
          {"target_frames", o.target_frames},
          {"tolerance", o.tolerance},
          {"block", o.block},
          {"light", r.light},
          {"offset", {r.offset.x, r.offset.y, r.offset.z}},
          {"move_fraction", o.move_fraction},
          {"change", r.applicable ? finite_or_null(r.change) : json()},
          {"errors", errors}};
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
      {"shadow_rays", r.settings.one_shadow_ray ? "one" : "all"},
      {"moving_lights", r.settings.moving_lights_apart ? "apart" : "history"},
      {"seed", r.settings.seed},
      {"accumulate", r.settings.accumulate},
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
        {"technique_per_s", per_second(r.technique_rays, r.technique_ms)}}},
      {"photons",
       {{"paths_per_frame", r.photon_paths / frames},
        {"stored_per_frame", r.photons_stored / frames},
        // Of those, kept from unchanged frame-coherent paths rather than traced again.
        {"reused_per_frame", r.photons_reused / frames},
        // Photon paths over the technique's time (prepare: tracing; indirect: estimation).
        {"paths_per_s", per_second(r.photon_paths, r.technique_ms)}}},
      {"flicker", flicker_json(r.temporal)},
      {"settle", settle_json(r.temporal)},
      {"resident_memory", r.memory == nullptr ? json()
                                              : json{{"frames", r.memory->frames},
                                                     {"bytes", r.memory->bytes},
                                                     {"growth_after_warmup", r.memory_growth}}},
  };
  save_text_file(path, record.dump(2) + "\n");
}

}  // namespace bounce::app
