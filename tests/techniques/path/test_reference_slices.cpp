// Reference slices: disjoint ranges of the per-pixel sample sequence, rendered apart and merged,
// give the image of one run over all of them, and slices that do not belong together are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/path/reference_slices.h"
#include "test_text.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 16;

ReferenceCheckpointKey key_of(int first, uint32_t seed = 3, int size = kSize) {
  return ReferenceCheckpointKey{"cornell at 0", size, size, seed, -1, 3, first};
}

// Renders samples [first, first + spp) of the built-in Cornell box.
Image render_slice(int first, int spp, uint32_t seed = 3, int size = kSize) {
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  ReferenceSettings settings;
  settings.width = settings.height = size;
  settings.spp = spp;
  settings.first_sample = first;
  settings.seed = seed;
  return render_reference(s, *tracer, s.camera, settings).image;
}

// A slice as bounce reference writes it and bounce merge reads it: through an EXR's header.
ReferenceSlice slice_file(const fs::path& dir, int first, int spp, uint32_t seed = 3,
                          int size = kSize) {
  const std::string path = (dir / ("slice_" + std::to_string(first) + "_" + std::to_string(seed) +
                                   "_" + std::to_string(size) + ".exr"))
                               .string();
  save_exr(path, render_slice(first, spp, seed, size),
           reference_attributes(key_of(first, seed, size), spp));
  return read_reference_slice(path);
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("bounce-slices-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Merged means were rounded to float once per slice and once more after merging, and the
// per-pixel double sums are added in another order than one run adds them: equal to about one
// float rounding (2^-24 relative), not bit for bit.
void expect_within_float_rounding(const Image& a, const Image& b) {
  ASSERT_EQ(a.pixel_count(), b.pixel_count());
  for (size_t i = 0; i < a.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = a.pixels()[i][c], y = b.pixels()[i][c];
      ASSERT_NEAR(x, y, 4e-7f * std::max(std::fabs(x), std::fabs(y)) + 1e-12f) << i << " " << c;
    }
}

TEST(ReferenceSlices, MergedSlicesEqualOneRun) {
  const fs::path dir = scratch("equal");
  const Image single = render_slice(0, 9);
  // Three slices of the nine samples, given out of order.
  const ReferenceSlice merged =
      merge_reference_slices({slice_file(dir, 5, 4), slice_file(dir, 0, 2), slice_file(dir, 2, 3)});
  EXPECT_EQ(merged.first, 0);
  EXPECT_EQ(merged.spp, 9);
  expect_within_float_rounding(merged.image, single);

  // The offset matters: a second slice that took samples 0.. again is another image.
  const Image head = render_slice(0, 2), repeated = render_slice(0, 7);
  double difference = 0.0;
  for (size_t i = 0; i < single.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c)
      difference += std::fabs((2.0 * head.pixels()[i][c] + 7.0 * repeated.pixels()[i][c]) / 9.0 -
                              single.pixels()[i][c]);
  EXPECT_GT(difference / (3.0 * single.pixel_count()), 1e-3);
}

TEST(ReferenceSlices, MergedImagesMergeAgain) {
  const fs::path dir = scratch("again");
  const ReferenceSlice first_half =
      merge_reference_slices({slice_file(dir, 0, 2), slice_file(dir, 2, 2)});
  const std::string path = (dir / "half.exr").string();
  save_exr(path, first_half.image, reference_attributes(first_half));
  const ReferenceSlice all =
      merge_reference_slices({read_reference_slice(path), slice_file(dir, 4, 2)});
  EXPECT_EQ(all.spp, 6);
  expect_within_float_rounding(all.image, render_slice(0, 6));
}

TEST(ReferenceSlices, SlicesThatDoNotBelongTogetherAreRefused) {
  const fs::path dir = scratch("refused");
  const ReferenceSlice a = slice_file(dir, 0, 2);
  const auto error_of = [](const std::vector<ReferenceSlice>& slices) {
    try {
      merge_reference_slices(slices);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_TRUE(test::contains(error_of({a, slice_file(dir, 1, 2)}), "overlaps"));
  EXPECT_TRUE(test::contains(error_of({a, slice_file(dir, 3, 2)}), "samples 2 .. 2 are missing"));
  EXPECT_TRUE(test::contains(error_of({a, slice_file(dir, 2, 2, 4)}), "seed=3"));
  EXPECT_TRUE(test::contains(error_of({a, slice_file(dir, 2, 2, 3, 8)}), "height=16"));
  EXPECT_TRUE(test::contains(error_of({}), "no reference slices"));
  // Paths that chose their lights differently (bounce reference --light-candidates).
  ReferenceCheckpointKey one_candidate = key_of(2);
  one_candidate.light_candidates = 1;
  const std::string other = (dir / "one_candidate.exr").string();
  save_exr(other, render_slice(2, 2), reference_attributes(one_candidate, 2));
  EXPECT_TRUE(test::contains(error_of({a, read_reference_slice(other)}), "light_candidates=8"));

  // An EXR without the header bounce reference writes is not a slice.
  const std::string plain = (dir / "plain.exr").string();
  save_image(plain, Image(4, 4));
  try {
    read_reference_slice(plain);
    ADD_FAILURE() << "a plain EXR was read as a slice";
  } catch (const Error& e) {
    EXPECT_TRUE(test::contains(e.what(), "not a bounce reference image")) << e.what();
  }
}

TEST(ReferenceSlices, OffsetsOutsideTheSequenceAreErrors) {
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  ReferenceSettings settings;
  settings.width = settings.height = 4;
  settings.spp = 2;
  settings.first_sample = -1;
  EXPECT_THROW(render_reference(s, *tracer, s.camera, settings), Error);
  settings.first_sample = kMaxReferenceSample - 1;
  EXPECT_THROW(render_reference(s, *tracer, s.camera, settings), Error);
}

}  // namespace
}  // namespace bounce
