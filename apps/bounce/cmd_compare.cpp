// bounce compare: metrics of an image against a reference, and an error heat map.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/metrics/flip.h"
#include "bounce/metrics/image_metrics.h"
#include "input_checks.h"
#include "options.h"

namespace bounce::app {

namespace {

struct CompareOptions {
  std::string reference;
  std::string test;
  std::string heatmap;
  double heatmap_max = 0.0;
  std::string flip_map;  // --flip-map: the FLIP error map as a grey PNG
  double flip_ppd = kFlipDefaultPpd;
  bool json = false;
};

nlohmann::json to_json(const DomainMetrics& m) {
  // JSON has no infinity or NaN: those become null (e.g. PSNR of identical images).
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  return {{"mse", m.mse},
          {"nrmse", number(m.nrmse)},
          {"range", m.range},
          {"psnr_db", number(m.psnr_db)},
          {"psnr_peak", m.peak},
          {"mssim", number(m.mssim)},
          {"ssim_range", m.ssim_range},
          {"ssim_windows", m.ssim_windows}};
}

std::string text(double v, const char* format) {
  if (std::isnan(v)) return "n/a";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format(fmt::runtime(format), v);
}

void print_row(const char* name, const DomainMetrics& m) {
  fmt::print("{:<8} {:>14} {:>10} {:>9} {:>8} {:>12}\n", name, text(m.mse, "{:.6g}"),
             text(m.nrmse, "{:.5f}"), text(m.psnr_db, "{:.2f}"), text(m.mssim, "{:.5f}"),
             text(m.range, "{:.6g}"));
}

void run_compare(const CompareOptions& o) {
  const Image reference = load_image(o.reference);
  const Image test = load_image(o.test);
  if (reference.width() != test.width() || reference.height() != test.height())
    fail("cannot compare {} ({}x{}) with {} ({}x{}): the sizes differ", o.reference,
         reference.width(), reference.height(), o.test, test.width(), test.height());
  const ImageComparison c = compare_images(reference, test);
  HeatMap heat;
  if (!o.heatmap.empty()) {
    if (!o.heatmap.ends_with(".png") && !o.heatmap.ends_with(".PNG"))
      fail("cannot write heat map {}: it must be a .png file", o.heatmap);
    heat = error_heat_map(reference, test, o.heatmap_max);
    save_png_rgb8(o.heatmap, heat.width, heat.height, heat.rgb.data());
  }
  if (!o.flip_map.empty() && !o.flip_map.ends_with(".png") && !o.flip_map.ends_with(".PNG"))
    fail("cannot write FLIP map {}: it must be a .png file", o.flip_map);
  const FlipMap flip = flip_map(reference, test, o.flip_ppd);
  if (!o.flip_map.empty())
    save_png_rgb8(o.flip_map, flip.width, flip.height, flip_grey_rgb8(flip).data());

  if (o.json) {
    nlohmann::json j = {{"reference", o.reference},
                        {"test", o.test},
                        {"width", c.width},
                        {"height", c.height},
                        {"srgb8", to_json(c.srgb8)},
                        {"linear", to_json(c.linear)},
                        {"flip", {{"mean", flip.mean}, {"ppd", flip.ppd}}}};
    if (!o.flip_map.empty()) j["flip"]["map"] = o.flip_map;
    if (!o.heatmap.empty())
      j["heatmap"] = {{"path", o.heatmap}, {"scale", heat.scale}, {"max_error", heat.max_error}};
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("reference {} ({}x{})\ntest      {}\n", o.reference, c.width, c.height, o.test);
  fmt::print("{:<8} {:>14} {:>10} {:>9} {:>8} {:>12}\n", "domain", "MSE", "NRMSE", "PSNR dB",
             "MSSIM", "ref range");
  print_row("srgb8", c.srgb8);
  print_row("linear", c.linear);
  fmt::print(
      "FLIP     {:>14}   (mean LDR-FLIP of the 8-bit sRGB images at {:.1f} pixels per degree)\n",
      text(flip.mean, "{:.6f}"), flip.ppd);
  fmt::print(
      "srgb8: 8-bit sRGB values (0..255) after the PNG tone map at exposure 0; linear: radiance.\n"
      "MSE per channel averaged over channels; NRMSE = sqrt(MSE) / reference range; PSNR peak "
      "255 (srgb8) or the reference range (linear); SSIM on luminance, 11x11 Gaussian window "
      "(sigma 1.5), windows inside the image only. FLIP: Andersson et al. 2020, 0 = identical, "
      "1 = the largest difference.\n");
  if (!o.flip_map.empty()) fmt::print("FLIP map {}: grey, black = 0, white = 1\n", o.flip_map);
  if (!o.heatmap.empty())
    fmt::print("heat map {}: per-pixel RMS sRGB error, ramp 0..{:.3g} (max {:.3g})\n", o.heatmap,
               heat.scale, heat.max_error);
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare an image B against a reference A: MSE, NRMSE, PSNR, SSIM/MSSIM, FLIP");
  cmd->add_option("reference", o->reference, "Reference image A (.exr, .pfm, .png, ...)")
      ->required();
  cmd->add_option("test", o->test, "Image B compared against A")->required();
  cmd->add_option("--heatmap", o->heatmap, "Write a per-pixel error heat map (PNG)")
      ->check(non_empty_path());
  cmd->add_option("--heatmap-max", o->heatmap_max,
                  "RMS sRGB error at the top of the heat map's ramp (0: the 99th percentile)")
      ->check(CLI::Range(0.0, 255.0))
      ->capture_default_str();
  cmd->add_option("--flip-map", o->flip_map,
                  "Write the per-pixel FLIP error map (PNG, grey: black 0, white 1)")
      ->check(non_empty_path());
  cmd->add_option("--flip-ppd", o->flip_ppd,
                  "FLIP's viewing distance as pixels per degree of visual angle (default: the "
                  "paper's 0.7 m wide 4K monitor at 0.7 m)")
      ->check(CLI::Range(0.01, 10000.0))
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print the metrics as JSON");
  cmd->callback([o] { run_compare(*o); });
}

}  // namespace bounce::app
