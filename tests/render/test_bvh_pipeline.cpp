// The whole CPU frame through our BVH (BvhTracer) against the same frame through Embree: what the
// CUDA backend traces on the GPU, checked on machines without one. The photon paths, shadow rays,
// clearance rays and primary rays all go through the tracer, so a BVH that lost triangles or
// reported other hits would change the image.
#include <gtest/gtest.h>

#include "bounce/metrics/image_metrics.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

namespace bounce {
namespace {

Image frame(const Scene& scene, Tracer& tracer, const std::string& technique, int frames) {
  Renderer renderer(scene, tracer, make_technique(technique));
  FrameSettings settings;
  settings.width = settings.height = 64;
  settings.light_samples = 4;
  settings.accumulate = true;
  settings.jitter = true;
  Image out;
  for (int k = 0; k < frames; ++k) out = renderer.render(scene.camera, settings).color;
  return out;
}

TEST(BvhPipeline, FramesThroughOurBvhEqualFramesThroughEmbree) {
  for (const char* spec : {"cornell", "cubes:200"}) {
    const Scene scene = load_scene(spec);
    auto embree = make_embree_tracer(scene);
    auto bvh = make_bvh_tracer(scene);
    for (const char* technique : {"direct", "tiled"}) {
      const Image a = frame(scene, *embree, technique, 4);
      const Image b = frame(scene, *bvh, technique, 4);
      const ImageComparison c = compare_images(a, b);
      // Hits agree to float rounding, so the sample patterns and photon slots are the same: the
      // images differ only where a ray grazes an edge.
      EXPECT_GT(c.srgb8.mssim, 0.995) << spec << " " << technique;
      EXPECT_LT(c.srgb8.mse, 0.5) << spec << " " << technique;
    }
  }
}

}  // namespace
}  // namespace bounce
