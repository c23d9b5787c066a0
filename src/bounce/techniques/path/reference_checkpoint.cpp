// A reference checkpoint file: a text header (a magic line, then NAME=VALUE lines naming the key
// and the samples taken, then "data"), followed by the per-pixel sums as 8-byte doubles in this
// machine's byte order. Text for what a person may want to read with `head`, binary for the sums,
// which must come back bit for bit for a resumed run to equal an uninterrupted one.
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/core/input_file.h"
#include "bounce/techniques/path/reference.h"

namespace bounce {

namespace {

constexpr const char* kMagic = "bounce reference checkpoint 1";
// The next-event estimate's scheme, so that samples of different schemes are never merged: 2
// resamples a sample of every light in scenes with 2 to 8 lights (1, before it, had no field
// and picked one light by power there).
constexpr const char* kNextEventVersion = "2";

}  // namespace

std::map<std::string, std::string> reference_key_fields(const ReferenceCheckpointKey& k) {
  return {{"scene", k.scene},
          {"width", std::to_string(k.width)},
          {"height", std::to_string(k.height)},
          {"seed", std::to_string(k.seed)},
          {"max_bounces", std::to_string(k.max_bounces)},
          {"rr_start", std::to_string(k.rr_start)},
          {"sample_offset", std::to_string(k.first_sample)},
          {"light_candidates", std::to_string(k.light_candidates)},
          {"next_event_version", kNextEventVersion}};
}

void save_reference_checkpoint(const std::string& path, const ReferenceCheckpointKey& key,
                               const ReferenceState& state) {
  std::string out = std::string(kMagic) + "\n";
  for (const auto& [name, value] : reference_key_fields(key)) out += name + "=" + value + "\n";
  out += "spp=" + std::to_string(state.spp) + "\ndata\n";
  const size_t bytes = state.sums.size() * sizeof(double);
  const size_t header = out.size();
  out.resize(header + bytes);
  std::memcpy(out.data() + header, state.sums.data(), bytes);
  save_text_file(path, out, true);
}

ReferenceState load_reference_checkpoint(const std::string& path,
                                         const ReferenceCheckpointKey& key) {
  check_regular_file(path, "reference checkpoint");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the reference checkpoint", path);
  std::string line;
  if (!std::getline(in, line) || line != kMagic)
    fail("{}: not a bounce reference checkpoint (its first line is not '{}')", path, kMagic);
  std::map<std::string, std::string> fields;
  while (std::getline(in, line) && line != "data") {
    const size_t eq = line.find('=');
    if (eq == std::string::npos || fields.size() > 16)
      fail("{}: damaged reference checkpoint header (line '{}')", path, line.substr(0, 80));
    fields[line.substr(0, eq)] = line.substr(eq + 1);
  }
  if (line != "data") fail("{}: damaged reference checkpoint: its header has no end", path);
  for (const auto& [name, value] : reference_key_fields(key)) {
    const auto found = fields.find(name);
    if (found == fields.end()) fail("{}: the reference checkpoint has no '{}'", path, name);
    if (found->second != value)
      fail(
          "{}: the checkpoint was made with {}={}, this run has {}={}; use another checkpoint "
          "file or the same settings",
          path, name, found->second, name, value);
  }
  ReferenceState state;
  state.width = key.width;
  state.height = key.height;
  const auto spp = fields.find("spp");
  if (spp == fields.end()) fail("{}: the reference checkpoint has no 'spp'", path);
  std::istringstream spp_text(spp->second);
  if (!(spp_text >> state.spp) || !spp_text.eof() || state.spp <= 0)
    fail("{}: damaged reference checkpoint: spp '{}'", path, spp->second);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t values = size_t(key.width) * size_t(key.height) * 3;
  if (data.size() != values * sizeof(double))
    fail("{}: damaged reference checkpoint: {} bytes of samples where {}x{} needs {}", path,
         data.size(), key.width, key.height, values * sizeof(double));
  state.sums.resize(values);
  std::memcpy(state.sums.data(), data.data(), data.size());
  return state;
}

}  // namespace bounce
