// Reference slices: a long reference split into runs over disjoint ranges of the per-pixel sample
// sequence (bounce reference --sample-offset K --spp N, on as many machines as there are), each
// an EXR whose header says what it is, merged back by bounce merge into the image of one run.
#pragma once

#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/image_io.h"
#include "bounce/techniques/path/reference.h"

namespace bounce {

// The EXR header attributes of a reference image: "bounce.reference.NAME" for every
// reference_key_fields() entry (the sample_offset among them) and "bounce.reference.spp", the
// samples per pixel it holds.
ImageAttributes reference_attributes(const ReferenceCheckpointKey& key, int spp);

struct ReferenceSlice;
// The same for a (merged) slice, so merged images can be merged again.
ImageAttributes reference_attributes(const ReferenceSlice& slice);

struct ReferenceSlice {
  std::string path;        // where it came from, for messages
  ImageAttributes fields;  // the key's fields without the sample range: equal across slices
  int first = 0;           // first sample index
  int spp = 0;             // samples per pixel it holds
  Image image;             // their mean
};

// Reads a reference EXR written by bounce reference; fails naming the file when it is not one
// (no attributes, or damaged ones).
ReferenceSlice read_reference_slice(const std::string& path);

// The samples-weighted mean of the slices (in double), with the merged range: the image of one
// run over samples [min first, min first + total spp). Fails, naming the files, when the slices
// differ in anything but their range (scene, size, seed, bounces), when ranges overlap (samples
// counted twice), or when they leave a gap (the result would not equal any single run).
ReferenceSlice merge_reference_slices(const std::vector<ReferenceSlice>& slices);

}  // namespace bounce
