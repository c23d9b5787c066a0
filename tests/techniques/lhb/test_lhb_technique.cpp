// The lhb technique against the path-traced Cornell box: indirect light through the layered hit
// buffers with two bounces lands near the reference, and dropping bounces shows.
#include <gtest/gtest.h>

#include "bounce/core/error.h"
#include "bounce/metrics/image_metrics.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_edit.h"
#include "bounce/techniques/lhb/lhb.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/registry.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

constexpr int kSize = 32;
// 8-bit MSE against the reference, 32 frames of 4 paths: measured 72 with two bounces, 145 with
// one, 1334 without indirect light (5 bounces: 45; two bounces over 128 frames: 29).
constexpr double kTwoBounceBound = 100.0;
// lowres 2, same frames: measured 73.0 (lowres 1: 72.1) with 462 of 1024 pixels edges.
constexpr double kLowResBound = 85.0;
// lowres 4 without edges or filter, same frames: measured 93.2 (lowres 1 with the filter: 72.6).
// At 32x32 a 4x4 block is an eighth of the image; at 512x512 the two score alike (docs/lhb.md,
// "Real-time defaults").
constexpr double kRealTimeBound = 110.0;

// The last of `frames` frames at rest: direct light and the per-frame indirect estimates
// averaged by the pipeline.
Image lhb_image(const Scene& scene, Tracer& tracer, int bounces, int frames, int paths,
                int interleave = 3, int lowres = 1, size_t* edge_pixels = nullptr) {
  auto technique = std::make_unique<LhbTechnique>();
  const LhbTechnique* lhb = technique.get();
  technique->settings().lowres = lowres;
  // At 32x32 a jittered pixel spans about 2% of the diagonal: the default gap (1%, sized for
  // 512x512) would call most pixels edges.
  technique->settings().edges.distance = 0.05f;
  // The bounds below were measured with the seed's discontinuity filter and tiled's edge test,
  // the defaults before real-time frames moved to coarser blocks without either.
  technique->settings().edges.normal = 0.99f;
  technique->settings().filter = true;
  technique->settings().bounces = bounces;
  technique->settings().paths = paths;
  technique->settings().interleave = interleave;
  Renderer renderer(scene, tracer, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 8;
  settings.jitter = true;  // the reference is box-filtered over each pixel
  settings.accumulate = true;
  const Frame* frame = nullptr;
  for (int k = 0; k < frames; ++k) frame = &renderer.render(scene.camera, settings);
  EXPECT_EQ(frame->frames_averaged, frames);
  if (edge_pixels) *edge_pixels = lhb->edge_pixels();
  return frame->color;
}

class LhbVsReference : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(make_cornell());
    tracer_ = make_embree_tracer(*scene_).release();
    ReferenceSettings rs;
    rs.width = rs.height = kSize;
    rs.spp = 1024;
    reference_ = new Image(render_reference(*scene_, *tracer_, scene_->camera, rs).image);
  }
  static void TearDownTestSuite() {
    delete reference_;
    delete tracer_;
    delete scene_;
  }
  static double mse8(const Image& image) { return compare_images(*reference_, image).srgb8.mse; }

  static Scene* scene_;
  static Tracer* tracer_;
  static Image* reference_;
};
Scene* LhbVsReference::scene_ = nullptr;
Tracer* LhbVsReference::tracer_ = nullptr;
Image* LhbVsReference::reference_ = nullptr;

TEST_F(LhbVsReference, TwoBouncesMatchTheReferenceAndDroppedBouncesShow) {
  const double two = mse8(lhb_image(*scene_, *tracer_, 2, 32, 4));
  const double one = mse8(lhb_image(*scene_, *tracer_, 1, 32, 4));
  const double none = mse8(lhb_image(*scene_, *tracer_, 0, 4, 1));
  RecordProperty("mse8_two_bounces", std::to_string(two));
  RecordProperty("mse8_one_bounce", std::to_string(one));
  RecordProperty("mse8_no_indirect", std::to_string(none));
  EXPECT_LT(two, kTwoBounceBound) << "one " << one << " none " << none;
  EXPECT_GT(none, kTwoBounceBound);
  EXPECT_GT(one, 1.3 * two) << "the second bounce must show";
}

TEST_F(LhbVsReference, HalfResolutionPathsStayNearFullResolution) {
  // Paths from one pixel in four, upsampled, with the edges (the box's silhouettes, the room's
  // corners) traced at full resolution: the error stays near the full-resolution one.
  size_t full_edges = 1, half_edges = 0;
  const double full = mse8(lhb_image(*scene_, *tracer_, 2, 32, 4, 3, 1, &full_edges));
  const double half = mse8(lhb_image(*scene_, *tracer_, 2, 32, 4, 3, 2, &half_edges));
  RecordProperty("mse8_lowres_1", std::to_string(full));
  RecordProperty("mse8_lowres_2", std::to_string(half));
  RecordProperty("edge_pixels_lowres_2", std::to_string(half_edges));
  EXPECT_EQ(full_edges, 0u);
  EXPECT_GT(half_edges, size_t(kSize));  // at least the silhouettes of the boxes
  EXPECT_LT(half_edges, size_t(kSize * kSize * 3 / 4));
  EXPECT_LT(half, kLowResBound) << "full resolution " << full;
  EXPECT_LT(half, 1.15 * full);
}

TEST_F(LhbVsReference, CoarsePathsWithoutEdgesOrFilterStayNearTheReference) {
  // The real-time defaults but for the block size, which they pick by the image's width (a
  // 32x32 image gets paths at every pixel): paths from one pixel in sixteen, no edge pixels
  // re-estimated and no discontinuity filter (the denoiser's filter does both jobs).
  // Accumulated at rest the error stays within kRealTimeBound, well under what dropping a bounce
  // costs (kTwoBounceBound's comment).
  auto technique = std::make_unique<LhbTechnique>();
  const LhbTechnique* lhb = technique.get();
  EXPECT_FALSE(lhb->settings().filter);
  technique->settings().lowres = 4;
  technique->settings().paths = 4;
  Renderer renderer(*scene_, *tracer_, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 8;
  settings.jitter = true;
  settings.accumulate = true;
  const Frame* frame = nullptr;
  for (int k = 0; k < 32; ++k) frame = &renderer.render(scene_->camera, settings);
  EXPECT_EQ(lhb->edge_pixels(), 0u);
  const double quarter = mse8(frame->color);
  const double full = mse8(lhb_image(*scene_, *tracer_, 2, 32, 4));
  RecordProperty("mse8_lowres_4_no_edges", std::to_string(quarter));
  RecordProperty("mse8_lowres_1_filtered", std::to_string(full));
  EXPECT_LT(quarter, kRealTimeBound) << "full resolution " << full;
}

TEST(LhbTechnique, PicksItsBlockSizeByTheImageWidth) {
  // About 85 blocks across, at most 6 x 6 pixels, and every pixel's paths on small images.
  EXPECT_EQ(LhbTechnique().settings().lowres, 0);
  EXPECT_EQ(lhb_auto_lowres(32), 1);
  EXPECT_EQ(lhb_auto_lowres(127), 1);
  EXPECT_EQ(lhb_auto_lowres(128), 2);
  EXPECT_EQ(lhb_auto_lowres(256), 3);
  EXPECT_EQ(lhb_auto_lowres(512), 6);
  EXPECT_EQ(lhb_auto_lowres(1920), 6);
}

TEST_F(LhbVsReference, BuffersTooLargeToAllocateAreAClearError) {
  auto technique = std::make_unique<LhbTechnique>();
  technique->settings().size = 4096;  // 320 x 4096^2 x 16 elements: 645 GiB
  Renderer renderer(*scene_, *tracer_, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = 8;
  EXPECT_THROW(renderer.render(scene_->camera, settings), Error);
}

// A ball moved through the renderer (Renderer::scene_changed, as the viewer and the animation
// do): with instances it is re-posed, not rasterized again, and the accumulated image matches
// both the seed's way (its slab rasterized again) and the path reference of the moved scene.
TEST(LhbTechnique, AMovedBallIsReposedThroughTheRenderer) {
  Scene scene = make_cornell();
  const vec3 lo = scene.bounds.lo, hi = scene.bounds.hi, size = hi - lo;
  scene.meshes.push_back(scene_test::bumpy_ball(16, lo + size * vec3(0.3f, 0.55f, 0.45f),
                                                0.12f * size.x, scene.meshes[0].materials[0]));
  scene.finalize();
  const uint32_t ball = uint32_t(scene.meshes.size() - 1);
  const auto tracer = make_embree_tracer(scene);
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 8;
  settings.jitter = true;
  settings.accumulate = true;
  const auto make = [&](int instances, const LhbTechnique*& lhb) {
    auto technique = std::make_unique<LhbTechnique>();
    lhb = technique.get();
    technique->settings().instances = instances;
    technique->settings().lowres = 1;
    technique->settings().paths = 4;
    technique->settings().filter = true;
    return std::make_unique<Renderer>(scene, *tracer, std::move(technique));
  };
  const LhbTechnique *with = nullptr, *without = nullptr;
  auto a = make(8, with), b = make(0, without);
  a->render(scene.camera, settings);
  b->render(scene.camera, settings);
  // The ball is static until it first moves; then it leaves the static buffers once.
  EXPECT_TRUE(with->buffers().dynamic_meshes().empty());
  const Frame* fa = nullptr;
  const Frame* fb = nullptr;
  for (const vec3 offset : {vec3(0.3f, -0.2f, 0.1f), vec3(-0.1f, 0.05f, -0.25f)}) {
    const SceneChange change = move_mesh(scene, ball, size * offset);
    a->scene_changed(change);
    b->scene_changed(change);
    for (int k = 0; k < 16; ++k) {
      fa = &a->render(scene.camera, settings);
      fb = &b->render(scene.camera, settings);
    }
  }
  EXPECT_EQ(with->buffers().instance_meshes(), std::vector<uint32_t>{ball});
  EXPECT_TRUE(without->buffers().instance_meshes().empty());
  const LhbStats sa = with->buffers().stats(), sb = without->buffers().stats();
  EXPECT_EQ(sa.instance_captures, 1u);  // when it first moved
  EXPECT_EQ(sa.instance_reposes, 2u);
  EXPECT_EQ(sa.dynamic_builds, 0u);
  EXPECT_EQ(sb.dynamic_builds, 2u);  // its slab, rasterized at each move

  ReferenceSettings rs;
  rs.width = rs.height = kSize;
  rs.spp = 1024;
  const Image reference = render_reference(scene, *tracer, scene.camera, rs).image;
  const double instance_error = compare_images(reference, fa->color).srgb8.mse;
  const double slab_error = compare_images(reference, fb->color).srgb8.mse;
  const double between = compare_images(fb->color, fa->color).srgb8.mse;
  RecordProperty("mse8_instance", std::to_string(instance_error));
  RecordProperty("mse8_slab", std::to_string(slab_error));
  RecordProperty("mse8_between", std::to_string(between));
  // Measured: 76.8 with instances, 76.5 rasterized again, 0.14 between them; a ball left where
  // it was first captured (the re-pose skipped) gives 88.5, and 2.65 between.
  EXPECT_LT(instance_error, kTwoBounceBound) << "slab " << slab_error;
  EXPECT_LT(instance_error, 1.1 * slab_error + 2.0);
  EXPECT_LT(between, 1.0) << "instance " << instance_error;
}

TEST(LhbTechnique, IsRegisteredWithItsParameters) {
  const auto technique = make_technique("lhb");
  ASSERT_EQ(technique->name(), "lhb");
  for (const char* name : {"direction_set", "directions", "size", "layers", "paths", "bounces",
                           "cone_radius", "interleave", "filter", "lowres", "edge_normal",
                           "edge_distance", "show_edges", "instances", "edge_misses"})
    EXPECT_NE(technique->params().find(name), nullptr) << name;
  EXPECT_THROW(technique->params().set("bounces", "-1"), Error);
  EXPECT_THROW(technique->params().set("directions", "100000"), Error);
}

}  // namespace
}  // namespace bounce
