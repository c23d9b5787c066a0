// bounce merge: reference slices rendered apart (bounce reference --sample-offset K --spp N, on
// other machines) combined into the image of one long run, weighted by their sample counts.
#include <fmt/format.h>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/techniques/path/reference_slices.h"
#include "input_checks.h"
#include "options.h"

namespace bounce::app {

namespace {

struct MergeOptions {
  std::string out;
  std::vector<std::string> inputs;
};

void run_merge(const MergeOptions& o) {
  if (lower_case_extension(o.out) != ".exr")
    fail("cannot write {}: bounce merge writes an .exr (it records the merged samples)", o.out);
  std::vector<ReferenceSlice> slices;
  for (const std::string& path : o.inputs) slices.push_back(read_reference_slice(path));
  const ReferenceSlice merged = merge_reference_slices(slices);
  save_exr(o.out, merged.image, reference_attributes(merged));
  fmt::print("merged {} slices: samples {} .. {} ({} spp) of {}\nwrote {}\n", slices.size(),
             merged.first, int64_t(merged.first) + merged.spp - 1, merged.spp,
             merged.fields.at("scene"), o.out);
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Combine reference slices (bounce reference --sample-offset K --spp N) into one image, "
      "weighted by their samples: equal to one run over all of them");
  cmd->add_option("out", o->out, "Merged image (.exr)")->required()->check(non_empty_path());
  cmd->add_option("inputs", o->inputs, "Slices (.exr written by bounce reference), any order")
      ->required();
  cmd->callback([o] { run_merge(*o); });
}

}  // namespace bounce::app
