// The denoiser against the path reference on the Cornell box at real-time settings (tiled's
// 2,000 photon paths and one light sample per frame), on a small image: the first frame, and
// frames at rest. The bounds sit between what the denoised and the raw pipeline score, so each
// test fails with the denoiser switched off.
#include <gtest/gtest.h>

#include "bounce/metrics/image_metrics.h"
#include "bounce/scene/load.h"
#include "render/render_test_util.h"

namespace bounce {
namespace {

using render_test::Job;

constexpr int kSize = 96;

const Image& reference() {
  static const Image image = render_test::path_reference(make_cornell(), kSize, kSize, 512);
  return image;
}

ImageComparison score(int frames, bool denoise) {
  Job job("tiled", kSize, kSize);
  job.light_samples = 1;
  job.frames = frames;
  job.jitter = true;
  job.denoise = denoise;
  return compare_images(reference(), render_test::render(make_cornell(), job).color);
}

TEST(DenoisedQuality, FirstFrameIsCloseToTheReference) {
  const ImageComparison raw = score(1, false), denoised = score(1, true);
  std::printf("first frame: raw MSE8 %.1f MSSIM %.4f, denoised MSE8 %.1f MSSIM %.4f\n",
              raw.srgb8.mse, raw.srgb8.mssim, denoised.srgb8.mse, denoised.srgb8.mssim);
  EXPECT_LT(denoised.srgb8.mse, 0.5 * raw.srgb8.mse);
  EXPECT_GT(denoised.srgb8.mssim, raw.srgb8.mssim + 0.1);
}

TEST(DenoisedQuality, FramesAtRestConvergeFasterThanTheRawPipeline) {
  const ImageComparison raw = score(16, false), denoised = score(16, true);
  std::printf("16 frames at rest: raw MSE8 %.1f MSSIM %.4f, denoised MSE8 %.1f MSSIM %.4f\n",
              raw.srgb8.mse, raw.srgb8.mssim, denoised.srgb8.mse, denoised.srgb8.mssim);
  EXPECT_LT(denoised.srgb8.mse, 0.9 * raw.srgb8.mse);
  EXPECT_GT(denoised.srgb8.mssim, raw.srgb8.mssim + 0.08);
}

}  // namespace
}  // namespace bounce
