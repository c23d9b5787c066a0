// tiled at rest against the path-traced reference of the same small Cornell box: progressive
// passes converge to it where independent frames do not, the default low-resolution estimate
// (lowres = 2) is as close as the full-resolution one, and the passes kept across a camera move
// keep the image as close after the move.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "bounce/metrics/image_metrics.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/tiled/tiled.h"
#include "render/render_test_util.h"

namespace bounce {
namespace {

constexpr int kSize = 32;
constexpr int kFrames = 64;
// 8-bit MSE against the reference that a converged image stays under. Measured: about 31 for
// 64 progressive frames, 320 for a single frame's indirect light and 880 for none at all.
constexpr double kConvergedMse8 = 80.0;
// The same two frames after a camera move stay under this with the passes kept.
constexpr double kMovedMse8 = 100.0;

const Scene& cornell() {
  static const Scene scene = make_cornell();
  return scene;
}

const Image& reference() {
  static const Image image = render_test::path_reference(cornell(), kSize, kSize, 256);
  return image;
}

double mse8(const Image& image) {
  return compare_images(reference(), image).srgb8.mse;
}

// `frames` jittered frames at rest: with accumulation, the pipeline's average of the direct
// light (box-filtered pixels, like the reference's) and tiled's own average of its passes.
render_test::Images tiled_at_rest(std::vector<std::pair<std::string, std::string>> params,
                                  int frames, bool accumulate = true) {
  render_test::Job job("tiled", kSize, kSize);
  job.params = std::move(params);
  job.light_samples = 4;
  job.frames = frames;
  job.jitter = true;
  job.accumulate = accumulate;
  return render_test::render(cornell(), job);
}

TEST(TiledProgressive, PassesConvergeToThePathTracedReference) {
  const double sixteen = mse8(tiled_at_rest({{"lowres", "1"}}, 16).color);
  const double converged = mse8(tiled_at_rest({{"lowres", "1"}}, kFrames).color);
  const double independent = mse8(tiled_at_rest({{"lowres", "1"}}, kFrames, false).color);
  RecordProperty("mse8_16_passes", std::to_string(sixteen));
  RecordProperty("mse8_64_passes", std::to_string(converged));
  RecordProperty("mse8_not_progressive", std::to_string(independent));
  EXPECT_LT(converged, 0.5 * sixteen);  // more passes, nearer the reference
  EXPECT_LT(converged, kConvergedMse8);
  // Without accumulation the last frame is one frame's noisy estimate: the bound is one that it
  // fails.
  EXPECT_GT(independent, kConvergedMse8);
}

TEST(TiledProgressive, DefaultLowResolutionMatchesTheReference) {
  ASSERT_EQ(make_technique("tiled")->params().find("lowres")->to_string(), "2")
      << "this test is about the default";
  const render_test::Images images = tiled_at_rest({}, kFrames);
  const double low = mse8(images.color);
  const double no_indirect = mse8(images.direct);
  RecordProperty("mse8_lowres_2", std::to_string(low));
  RecordProperty("mse8_no_indirect", std::to_string(no_indirect));
  EXPECT_LT(low, kConvergedMse8);
  // The same frames with the indirect light left out: the bound is one that it fails.
  EXPECT_GT(no_indirect, kConvergedMse8);
}

// The last of `at_b` frames at rest from camera B, after `at_a` frames at rest from the scene's
// camera A: the photons of up to `history_passes` passes carry over the move.
Image after_camera_move(const Scene& scene, const Camera& b, int history_passes, int at_a,
                        int at_b) {
  auto tracer = make_embree_tracer(scene);
  auto technique = std::make_unique<TiledPhotonMapping>();
  technique->settings().history_passes = history_passes;
  technique->settings().lowres = 1;
  technique->settings().motion_lowres = 1;
  Renderer renderer(scene, *tracer, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 16;  // direct light, which restarts at the move, near converged
  settings.jitter = true;
  settings.accumulate = true;
  for (int k = 0; k < at_a; ++k) renderer.render(scene.camera, settings);
  const Frame* f = nullptr;
  for (int k = 0; k < at_b; ++k) f = &renderer.render(b, settings);
  return f->color;
}

TEST(TiledProgressive, PassesKeptAcrossACameraMoveKeepTheImageNearTheReference) {
  Scene moved = cornell();
  moved.camera.position += vec3(0.08f, 0.05f, 0.15f);
  moved.camera.look_at += vec3(-0.06f, -0.03f, 0.0f);
  const Image reference_b = render_test::path_reference(moved, kSize, kSize, 256);
  const auto mse8_b = [&](const Image& image) {
    return compare_images(reference_b, image).srgb8.mse;
  };
  // 32 passes from A, then 2 frames from B: 17 passes (15 kept from A) or only the 2 from B.
  const double kept = mse8_b(after_camera_move(cornell(), moved.camera, 16, 32, 2));
  const double restarted = mse8_b(after_camera_move(cornell(), moved.camera, 1, 32, 2));
  RecordProperty("mse8_kept", std::to_string(kept));
  RecordProperty("mse8_restarted", std::to_string(restarted));
  // Measured: about 56 kept, 173 restarted.
  EXPECT_LT(kept, kMovedMse8);
  // Without the kept passes the image restarts at the move: the bound is one that it fails.
  EXPECT_GT(restarted, kMovedMse8);
}

}  // namespace
}  // namespace bounce
