// The CUDA pipeline against the CPU's: the same frames (same seed, same sample patterns) from
// the same kernel bodies, traced through our BVH on the GPU and Embree on the CPU. Images agree
// within a metric bound, not bit for bit: the two trace different triangle tests, and the GPU
// contracts float arithmetic differently.
#include <gtest/gtest.h>

#include "bounce/gpu/cuda_pipeline.h"
#include "bounce/metrics/image_metrics.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
#include "bounce/techniques/tiled/tiled.h"
#include "gpu_test_util.h"

namespace bounce {
namespace {

struct Pair {
  Image cpu, gpu;
};

// Renders `frames` frames of `technique` at rest on both backends; returns the last of each.
Pair render_both(const std::string& scene_spec, const std::string& technique, int frames,
                 bool accumulate, bool denoise = false, int size = 128) {
  Scene scene = load_scene(scene_spec);
  FrameSettings settings;
  settings.width = settings.height = size;
  settings.light_samples = 4;
  settings.accumulate = accumulate;
  settings.jitter = accumulate;
  settings.seed = 5;
  settings.denoise = denoise;
  Pair out;
  for (int device = 0; device < 2; ++device) {
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique(technique));
    if (device) renderer.set_device(make_cuda_pipeline());
    const Frame* f = nullptr;
    for (int k = 0; k < frames; ++k) f = &renderer.render(scene.camera, settings);
    (device ? out.gpu : out.cpu) = f->color;
  }
  return out;
}

TEST(CudaPipeline, DirectLightMatchesTheCpu) {
  BOUNCE_REQUIRE_GPU();
  const Pair p = render_both("cornell", "direct", 1, false);
  const ImageComparison c = compare_images(p.cpu, p.gpu);
  EXPECT_GT(c.srgb8.mssim, 0.995);
  EXPECT_LT(c.srgb8.mse, 1.0);
}

TEST(CudaPipeline, TiledMatchesTheCpuFrameByFrameAndConverged) {
  BOUNCE_REQUIRE_GPU();
  // One real-time frame: the same photons (same paths, slots and radius) give the same blotches.
  const Pair one = render_both("cornell", "tiled", 1, false);
  const ImageComparison c1 = compare_images(one.cpu, one.gpu);
  EXPECT_GT(c1.srgb8.mssim, 0.97);
  // Sixteen passes averaged at rest.
  const Pair many = render_both("cornell", "tiled", 16, true);
  const ImageComparison c16 = compare_images(many.cpu, many.gpu);
  EXPECT_GT(c16.srgb8.mssim, 0.98);
  EXPECT_LT(c16.srgb8.mse, 10.0);
  // And the GPU's indirect light is there: the direct-only frame differs clearly.
  const Pair direct = render_both("cornell", "direct", 16, true);
  EXPECT_LT(compare_images(many.gpu, direct.gpu).srgb8.mssim, 0.95);
}

TEST(CudaPipeline, DenoisedFramesMatchTheCpu) {
  BOUNCE_REQUIRE_GPU();
  // The first frame (filtered alone) and the eighth (history at rest) of the viewer's pipeline.
  for (int frames : {1, 8}) {
    const Pair p = render_both("cornell", "tiled", frames, true, true);
    const Pair raw = render_both("cornell", "tiled", frames, true, false);
    const ImageComparison c = compare_images(p.cpu, p.gpu);
    EXPECT_GT(c.srgb8.mssim, 0.98) << frames;
    // The filter did something: the GPU's denoised frame is nearer the CPU's than a raw one.
    EXPECT_LT(c.srgb8.mse, compare_images(p.cpu, raw.gpu).srgb8.mse) << frames;
  }
}

TEST(CudaPipeline, AMovingCameraStillMatches) {
  BOUNCE_REQUIRE_GPU();
  Scene scene = load_scene("cornell");
  FrameSettings settings;
  settings.width = settings.height = 96;
  settings.light_samples = 2;
  settings.accumulate = false;  // each frame on its own: the two keep different histories
  Image last[2];
  for (int device = 0; device < 2; ++device) {
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique("tiled"));
    if (device) renderer.set_device(make_cuda_pipeline());
    Camera camera = scene.camera;
    for (int k = 0; k < 6; ++k) {
      camera.position.x += 0.01f;
      last[device] = renderer.render(camera, settings).color;
    }
  }
  EXPECT_GT(compare_images(last[0], last[1]).srgb8.mssim, 0.97);
}

}  // namespace
}  // namespace bounce
