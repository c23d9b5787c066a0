// tiled converges towards the path-traced reference as photons grow and the radius shrinks.
#include <gtest/gtest.h>

#include "bounce/eval/render_image.h"
#include "bounce/metrics/image_metrics.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/tiled/tiled.h"

namespace bounce {
namespace {

constexpr int kSize = 32;

// What `passes` frames at rest show: the last frame, in which the pipeline has averaged direct
// light and tiled its shrinking-radius passes. `equal_weights`, when given, receives what the old
// `bounce render` wrote instead: every frame's image averaged again with equal weights.
Image tiled_image(const Scene& scene, Tracer& tracer, int passes, int photons, int lowres = 1,
                  Image* equal_weights = nullptr) {
  auto technique = std::make_unique<TiledPhotonMapping>();
  technique->settings().photons = photons;
  technique->settings().lowres = lowres;
  Renderer renderer(scene, tracer, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 8;
  settings.jitter = true;  // the reference is box-filtered over each pixel
  settings.accumulate = true;
  Image sum(kSize, kSize);
  const Frame* frame = nullptr;
  for (int k = 0; k < passes; ++k) {
    frame = &renderer.render(scene.camera, settings);
    sum += frame->color;
  }
  EXPECT_EQ(frame->frames_averaged, passes);
  if (equal_weights) *equal_weights = sum * (1.0f / float(passes));
  return frame->color;
}

Image cornell_reference(const Scene& scene, const Tracer& tracer) {
  ReferenceSettings rs;
  rs.width = rs.height = kSize;
  rs.spp = 1024;
  return render_reference(scene, tracer, scene.camera, rs).image;
}

TEST(TiledVsReference, ConvergesTowardsThePathTracedCornellBox) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const Image reference = cornell_reference(scene, *tracer);

  const double coarse = compare_images(reference, tiled_image(scene, *tracer, 2, 1000)).srgb8.mse;
  const double fine = compare_images(reference, tiled_image(scene, *tracer, 64, 8000)).srgb8.mse;
  const double direct_only =
      compare_images(reference, render_image(scene, "direct", FrameSettings{kSize, kSize, 64}, 16))
          .srgb8.mse;
  RecordProperty("mse_coarse", std::to_string(coarse));
  RecordProperty("mse_fine", std::to_string(fine));
  RecordProperty("mse_direct_only", std::to_string(direct_only));
  EXPECT_LT(fine, coarse);
  EXPECT_LT(fine, 0.05 * direct_only);  // the indirect light is there, and right
  EXPECT_LT(fine, 20.0);                // 8-bit MSE: within a few levels per pixel
}

// tiled's frames at rest are already a running average of passes whose radius shrinks; averaging
// them again with equal weights over-weights the first, blurrier passes. The pipeline's
// accumulation does not, and lands closer to the reference than the old double averaging.
TEST(TiledVsReference, AccumulatedPassesAreNotAveragedAgain) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const Image reference = cornell_reference(scene, *tracer);
  Image equal_weights;
  const Image accumulated = tiled_image(scene, *tracer, 64, 4000, 1, &equal_weights);
  const double mse = compare_images(reference, accumulated).srgb8.mse;
  const double mse_equal = compare_images(reference, equal_weights).srgb8.mse;
  RecordProperty("mse_accumulated", std::to_string(mse));
  RecordProperty("mse_equal_weights", std::to_string(mse_equal));
  EXPECT_LT(mse, 0.6 * mse_equal) << mse << " vs " << mse_equal;
}

}  // namespace
}  // namespace bounce
