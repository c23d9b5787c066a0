#include "bounce/techniques/path/reference_slices.h"

#include <algorithm>
#include <charconv>
#include <cstdint>

#include "bounce/core/error.h"

namespace bounce {

namespace {

constexpr const char* kPrefix = "bounce.reference.";

int parse_count(const std::string& path, const std::string& name, const std::string& text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 0 ||
      value > kMaxReferenceSample)
    fail("{}: damaged reference header: {}{} is '{}', not a sample count", path, kPrefix, name,
         text);
  return value;
}

}  // namespace

ImageAttributes reference_attributes(const ReferenceCheckpointKey& key, int spp) {
  ReferenceSlice slice;
  slice.fields = reference_key_fields(key);
  slice.fields.erase("sample_offset");
  slice.first = key.first_sample;
  slice.spp = spp;
  return reference_attributes(slice);
}

ImageAttributes reference_attributes(const ReferenceSlice& slice) {
  ImageAttributes a;
  for (const auto& [name, value] : slice.fields) a[kPrefix + name] = value;
  a[std::string(kPrefix) + "sample_offset"] = std::to_string(slice.first);
  a[std::string(kPrefix) + "spp"] = std::to_string(slice.spp);
  return a;
}

ReferenceSlice read_reference_slice(const std::string& path) {
  ImageAttributes attributes;
  ReferenceSlice slice;
  slice.path = path;
  slice.image = load_exr(path, attributes);
  const std::string prefix = kPrefix;
  for (const auto& [name, value] : attributes)
    if (name.starts_with(prefix)) slice.fields[name.substr(prefix.size())] = value;
  for (const auto& [name, value] : reference_key_fields(ReferenceCheckpointKey{}))
    if (!slice.fields.contains(name))
      fail(
          "{}: not a bounce reference image: its EXR header has no {}{} (write it with bounce "
          "reference -o FILE.exr)",
          path, prefix, name);
  if (!slice.fields.contains("spp"))
    fail("{}: not a bounce reference image: its EXR header has no {}spp", path, prefix);
  slice.first = parse_count(path, "sample_offset", slice.fields["sample_offset"]);
  slice.spp = parse_count(path, "spp", slice.fields["spp"]);
  if (slice.spp == 0) fail("{}: the reference holds no samples", path);
  if (slice.first > kMaxReferenceSample - slice.spp)
    fail("{}: damaged reference header: samples {} + {} run past the sequence", path, slice.first,
         slice.spp);
  const std::string width = std::to_string(slice.image.width());
  const std::string height = std::to_string(slice.image.height());
  if (slice.fields["width"] != width || slice.fields["height"] != height)
    fail("{}: damaged reference: the header says {}x{}, the pixels are {}x{}", path,
         slice.fields["width"], slice.fields["height"], width, height);
  slice.fields.erase("sample_offset");
  slice.fields.erase("spp");
  return slice;
}

ReferenceSlice merge_reference_slices(const std::vector<ReferenceSlice>& slices) {
  if (slices.empty()) fail("merge: no reference slices given");
  const ReferenceSlice& first = slices.front();
  for (const ReferenceSlice& s : slices) {
    for (const auto& [name, value] : first.fields) {
      const auto other = s.fields.find(name);
      const std::string theirs = other == s.fields.end() ? "(none)" : other->second;
      if (theirs != value)
        fail("merge: {} has {}={} but {} has {}={}: slices must be of one scene, view and setting",
             first.path, name, value, s.path, name, theirs);
    }
    if (s.fields.size() != first.fields.size())
      fail("merge: {} and {} record different settings", first.path, s.path);
    if (s.image.width() != first.image.width() || s.image.height() != first.image.height())
      fail("merge: {} is {}x{} but {} is {}x{}", first.path, first.image.width(),
           first.image.height(), s.path, s.image.width(), s.image.height());
  }
  std::vector<const ReferenceSlice*> order;
  for (const ReferenceSlice& s : slices) order.push_back(&s);
  std::stable_sort(
      order.begin(), order.end(),
      [](const ReferenceSlice* a, const ReferenceSlice* b) { return a->first < b->first; });
  int64_t next = order.front()->first;
  for (const ReferenceSlice* s : order) {
    const auto end = [](const ReferenceSlice* r) { return int64_t(r->first) + r->spp; };
    if (s->first < next)
      fail(
          "merge: {} (samples {} .. {}) overlaps an earlier slice, which ends at sample {}: "
          "samples would count twice",
          s->path, s->first, end(s) - 1, next - 1);
    if (s->first > next)
      fail(
          "merge: samples {} .. {} are missing before {} (render them with --sample-offset {} "
          "--spp {})",
          next, s->first - 1, s->path, next, s->first - next);
    next = end(s);
  }

  ReferenceSlice merged;
  merged.path = "merged";
  merged.fields = first.fields;
  merged.first = order.front()->first;
  merged.spp = int(next - merged.first);
  const size_t n = first.image.pixel_count();
  std::vector<double> sums(3 * n, 0.0);
  for (const ReferenceSlice* s : order) {
    const vec3* p = s->image.data();
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) sums[3 * i + c] += double(p[i][c]) * s->spp;
  }
  merged.image = Image(first.image.width(), first.image.height());
  const double inv = 1.0 / merged.spp;
  for (size_t i = 0; i < n; ++i)
    merged.image.pixels()[i] =
        vec3(float(sums[3 * i] * inv), float(sums[3 * i + 1] * inv), float(sums[3 * i + 2] * inv));
  return merged;
}

}  // namespace bounce
