// The offline reference and the `path` technique in the frame pipeline: they agree on the
// Cornell box, they do not depend on the thread count, and the driver honours its settings.
#include <gtest/gtest.h>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/path/path_technique.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/registry.h"
#include "path_test_util.h"
#include "render/render_test_util.h"

namespace bounce {
namespace {

constexpr int kSize = 32;

Image reference_image(const Scene& s, int spp, uint32_t seed, int max_bounces = -1) {
  return render_test::path_reference(s, kSize, kSize, spp, seed, max_bounces);
}

// Direct stage plus the technique's indirect term, averaged over jittered frames at rest.
Image pipeline_image(const Scene& s, int frames, uint32_t seed, int max_bounces = -1) {
  render_test::Job job("path", kSize, kSize);
  job.params = {{"seed", std::to_string(seed)}, {"max_bounces", std::to_string(max_bounces)}};
  job.light_samples = 4;
  job.frames = frames;
  job.jitter = true;
  job.seed = seed;
  return render_test::render(s, job).color;
}

// Mean of each quadrant and of the whole image, per channel, over independent runs.
struct RegionMeans {
  static constexpr int kRegions = 5;
  std::vector<path_test::Estimate> regions = std::vector<path_test::Estimate>(kRegions);
  void add(const Image& image) {
    const int h = kSize / 2;
    regions[0].add(mean(image, 0, 0, h, h));
    regions[1].add(mean(image, h, 0, kSize, h));
    regions[2].add(mean(image, 0, h, h, kSize));
    regions[3].add(mean(image, h, h, kSize, kSize));
    regions[4].add(mean(image));
  }
};

TEST(PathReference, AgreesWithDirectStagePlusPathIndirectOnTheCornellBox) {
  const Scene s = make_cornell();
  for (int bounces : {1, -1}) {
    RegionMeans ref, pipe;
    for (uint32_t seed = 1; seed <= 8; ++seed) {
      ref.add(reference_image(s, 64, seed, bounces));
      pipe.add(pipeline_image(s, 64, seed, bounces));
    }
    for (int r = 0; r < RegionMeans::kRegions; ++r)
      for (int k = 0; k < 3; ++k) {
        const double a = ref.regions[r].mean(k), b = pipe.regions[r].mean(k);
        // The spread over 8 seeds bounds the noise; the tolerance is 5 standard errors.
        const double se =
            std::hypot(ref.regions[r].standard_error(k), pipe.regions[r].standard_error(k));
        EXPECT_NEAR(a, b, 5.0 * se + 1e-6)
            << "bounces " << bounces << " region " << r << " channel " << k;
        EXPECT_LT(se, 0.01 * a) << "too noisy to test anything";
      }
  }
}

TEST(PathReference, MoreBouncesGiveMoreLight) {
  const Scene s = make_cornell();
  const vec3 b0 = mean(reference_image(s, 16, 1, 0));
  const vec3 b1 = mean(reference_image(s, 16, 1, 1));
  const vec3 all = mean(reference_image(s, 16, 1, -1));
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(b0[k], b1[k]);
    EXPECT_LT(b1[k], all[k]);
  }
  // Direct light alone: the reference with 0 bounces against the direct stage. Pixels on the
  // light's edges are the noisiest, so this takes more samples than the ordering above.
  const vec3 reference = mean(reference_image(s, 256, 2, 0));
  const vec3 direct = mean(pipeline_image(s, 256, 2, 0));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(direct[k], reference[k], 0.01 * reference[k]);
}

TEST(PathReference, SameImageWhateverTheThreadCount) {
  const Scene s = make_cornell();
  Image one, two, pipe_one, pipe_two;
  {
    const ThreadLimit limit(1);
    one = reference_image(s, 4, 3);
    pipe_one = pipeline_image(s, 3, 3);
  }
  {
    const ThreadLimit limit(2);
    two = reference_image(s, 4, 3);
    pipe_two = pipeline_image(s, 3, 3);
  }
  EXPECT_EQ(one.pixels(), two.pixels());
  EXPECT_EQ(pipe_one.pixels(), pipe_two.pixels());
  EXPECT_NE(one.pixels(), reference_image(s, 4, 4).pixels()) << "the seed must matter";
}

TEST(PathReference, PassSizesDoNotChangeTheImage) {
  // A time limit makes the driver take one sample per pass at first; the same spp without one
  // takes bigger passes. Per-pixel sums in sample order make both the same.
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  ReferenceSettings settings;
  settings.width = settings.height = 16;
  settings.spp = 6;
  const Image a = render_reference(s, *tracer, s.camera, settings).image;
  settings.time_limit_s = 1000.0;
  int calls = 0, last = 0;
  const ReferenceResult r =
      render_reference(s, *tracer, s.camera, settings, [&](const ReferenceProgress& p) {
        ++calls;
        EXPECT_GT(p.spp_done, last);
        EXPECT_GE(p.eta_s, 0.0);
        last = p.spp_done;
      });
  EXPECT_EQ(r.spp, 6);
  EXPECT_GE(calls, 1);
  EXPECT_EQ(last, 6);
  EXPECT_EQ(a.pixels(), r.image.pixels());
}

TEST(PathReference, TimeLimitStopsEarly) {
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  ReferenceSettings settings;
  settings.width = settings.height = 16;
  settings.spp = 1 << 24;
  settings.time_limit_s = 0.3;
  const ReferenceResult r = render_reference(s, *tracer, s.camera, settings);
  EXPECT_GE(r.spp, 1);
  EXPECT_LT(r.spp, settings.spp);
  const vec3 m = mean(r.image);
  for (int c = 0; c < 3; ++c) EXPECT_GT(m[c], 0.0f) << c;
}

TEST(PathReference, EmittersSeenDirectlyShowTheirRadiance) {
  Scene s = path_test::furnace(vec3(0.5f), vec3(0.0f));  // a dark closed room
  s.lights.push_back(Light::sphere(vec3(0.0f, 0.0f, 0.6f), 0.3f, vec3(7.0f, 5.0f, 3.0f)));
  s.camera.look_at = vec3(0.0f, 0.0f, 1.0f);
  s.finalize();
  const Image image = reference_image(s, 4, 1);
  // The centre pixels look straight at the sphere; a sphere light reflects nothing.
  EXPECT_EQ(image.at(kSize / 2, kSize / 2), vec3(7.0f, 5.0f, 3.0f));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(image.at(0, 0)[c], 0.0f) << c;  // the walls it lights
    EXPECT_LT(image.at(0, 0)[c], vec3(7.0f, 5.0f, 3.0f)[c]) << c;
  }
}

TEST(PathReference, BadSettingsAreErrors) {
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  ReferenceSettings settings;
  settings.spp = 0;
  EXPECT_THROW(render_reference(s, *tracer, s.camera, settings), Error);
  settings.spp = 1;
  settings.width = 0;
  EXPECT_THROW(render_reference(s, *tracer, s.camera, settings), Error);
}

TEST(PathTechnique, AccumulatesUntilTheCameraOrAParameterChanges) {
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  auto owned = std::make_unique<PathTracing>();
  PathTracing& path = *owned;
  Renderer renderer(s, *tracer, std::move(owned));
  FrameSettings settings;
  settings.width = settings.height = 8;
  settings.accumulate = true;
  renderer.render(s.camera, settings);
  renderer.render(s.camera, settings);
  EXPECT_EQ(path.accumulated_frames(), 2);
  Camera moved = s.camera;
  moved.position.x += 0.01f;
  renderer.render(moved, settings);
  EXPECT_EQ(path.accumulated_frames(), 1);
  renderer.render(moved, settings);
  EXPECT_EQ(path.accumulated_frames(), 2);
  path.params().set("max_bounces", "2");
  renderer.render(moved, settings);
  EXPECT_EQ(path.accumulated_frames(), 1);
  renderer.render(moved, settings);
  renderer.scene_changed(SceneChange{{}, true});
  renderer.render(moved, settings);
  EXPECT_EQ(path.accumulated_frames(), 1);
  settings.accumulate = false;  // every frame a fresh estimate
  renderer.render(moved, settings);
  renderer.render(moved, settings);
  EXPECT_EQ(path.accumulated_frames(), 1);
}

}  // namespace
}  // namespace bounce

namespace bounce {
namespace {

TEST(PathReference, AResumedRunEqualsAnUninterruptedOne) {
  const Scene s = make_cornell();
  auto tracer = make_embree_tracer(s);
  ReferenceSettings settings;
  settings.width = settings.height = 12;
  settings.spp = 7;
  const Image whole = render_reference(s, *tracer, s.camera, settings).image;
  ReferenceState state;
  settings.spp = 3;
  render_reference(s, *tracer, s.camera, settings, {}, &state);
  EXPECT_EQ(state.spp, 3);
  // Through a checkpoint file and back, bit for bit.
  const std::string path = ::testing::TempDir() + "/bounce-resume.ckpt";
  const ReferenceCheckpointKey key{"cornell", 12, 12, 0, -1, 3};
  save_reference_checkpoint(path, key, state);
  ReferenceState loaded = load_reference_checkpoint(path, key);
  EXPECT_EQ(loaded.sums, state.sums);
  settings.spp = 7;
  const ReferenceResult resumed = render_reference(s, *tracer, s.camera, settings, {}, &loaded);
  EXPECT_EQ(resumed.spp, 7);
  EXPECT_EQ(resumed.image.pixels(), whole.pixels());
  // A key that differs in anything is refused.
  ReferenceCheckpointKey other = key;
  other.max_bounces = 2;
  EXPECT_THROW(load_reference_checkpoint(path, other), Error);
}

}  // namespace
}  // namespace bounce
