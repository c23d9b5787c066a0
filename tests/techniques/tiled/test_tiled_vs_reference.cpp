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

Image tiled_image(const Scene& scene, Tracer& tracer, int passes, int photons) {
  auto technique = std::make_unique<TiledPhotonMapping>();
  technique->settings().photons = photons;
  technique->settings().lowres = 1;
  Renderer renderer(scene, tracer, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 8;
  settings.jitter = true;  // the reference is box-filtered over each pixel
  Image sum(kSize, kSize);
  for (int k = 0; k < passes; ++k) sum += renderer.render(scene.camera, settings).color;
  return sum * (1.0f / float(passes));
}

TEST(TiledVsReference, ConvergesTowardsThePathTracedCornellBox) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  ReferenceSettings rs;
  rs.width = rs.height = kSize;
  rs.spp = 1024;
  const Image reference = render_reference(scene, *tracer, scene.camera, rs).image;

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

}  // namespace
}  // namespace bounce
