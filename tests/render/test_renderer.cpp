#include <gtest/gtest.h>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/eval/render_image.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
#include "render/render_test_util.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

Image render_with_threads(const Scene& scene, int threads) {
  render_test::Job job("direct", 48, 40);
  job.light_samples = 4;
  job.frames = 3;
  job.jitter = true;
  job.threads = threads;
  return render_test::render(scene, job).color;
}

TEST(Renderer, ImagesAreIdenticalWhateverTheThreadCount) {
  const Scene scene = make_cornell();
  const Image one = render_with_threads(scene, 1);
  const Image two = render_with_threads(scene, 2);
  ASSERT_EQ(one.pixel_count(), two.pixel_count());
  for (size_t i = 0; i < one.pixel_count(); ++i) ASSERT_EQ(one.pixels()[i], two.pixels()[i]) << i;
}

TEST(Renderer, TimesEveryStageAndCountsRays) {
  const Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  FrameSettings settings;
  settings.width = 16;
  settings.height = 8;
  settings.light_samples = 2;
  const Frame& f = renderer.render(scene.camera, settings);
  std::vector<std::string> names;
  for (const auto& s : f.times.stages()) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"scene", "prepare", "gbuffer", "direct", "composite",
                                             "tonemap"}));
  EXPECT_EQ(f.primary_rays, 16u * 8u);
  // At most two shadow rays per pixel (one area light, two samples), some below its horizon.
  EXPECT_GT(f.shadow_rays, 0u);
  EXPECT_LE(f.shadow_rays, 2u * 16u * 8u);
  EXPECT_EQ(f.ldr.size(), 16u * 8u * 3u);
  EXPECT_EQ(renderer.frame_index(), 1u);
  settings.width = 0;
  EXPECT_THROW(renderer.render(scene.camera, settings), Error);
}

TEST(Renderer, JitteredFramesAverageToTheBoxFilteredPixel) {
  // The average over a pixel of a sharp vertical edge is its covered fraction: a pixel split
  // by an emitter's edge converges to the fraction of the pixel the emitter covers.
  Scene s;
  s.source = "edge";
  Material emitter;
  emitter.albedo = vec3(0.0f);
  const vec3 radiance(1.0f, 0.5f, 0.25f);
  emitter.emission = radiance;
  s.materials.push_back(emitter);
  // Covers x >= 0 in the plane z = 1, facing the camera at the origin (normal -z).
  s.meshes.push_back(
      scene_test::quad_mesh("half", vec3(0, -10, 1), vec3(0, 20, 0), vec3(10, 0, 0), 0));
  s.camera.position = vec3(0.0f);
  s.camera.look_at = vec3(0.0f, 0.0f, 1.0f);
  s.camera.vfov_deg = 90.0f;
  s.has_camera = true;
  s.finalize();
  render_test::Job job("direct", 3, 3);  // the middle column straddles x = 0
  job.light_samples = 1;
  job.frames = 64;
  job.jitter = true;
  const Image image = render_test::render(s, job).color;
  // Image +x is world -x here (right = forward x up), so the emitter fills the left column.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(image.at(0, 1)[c], radiance[c], 1e-6f) << c;
    EXPECT_NEAR(image.at(2, 1)[c], 0.0f, 1e-6f) << c;
    EXPECT_NEAR(image.at(1, 1)[c], 0.5f * radiance[c], 0.02f * radiance[c]) << c;
  }
}

}  // namespace
}  // namespace bounce
