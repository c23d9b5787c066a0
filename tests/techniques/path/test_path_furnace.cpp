// White furnace: inside a closed cube whose walls reflect with albedo a and emit radiance Le,
// every point sees Le / (1 - a) with unlimited bounces and Le (1 + a + ... + a^(B+1)) when light
// may bounce at most B times before the visible point (B = 0: direct light only).
#include <gtest/gtest.h>

#include "bounce/render/renderer.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/registry.h"
#include "path_test_util.h"
#include "render/render_test_util.h"

namespace bounce {
namespace {

using path_test::furnace;
using path_test::geometric_sum;

const vec3 kAlbedo(0.3f, 0.5f, 0.7f);
const vec3 kRadiance(1.0f, 1.0f, 1.0f);

vec3 reference_mean(const Scene& scene, int max_bounces, int rr_start, int spp) {
  auto tracer = make_embree_tracer(scene);
  ReferenceSettings settings;
  settings.width = settings.height = 16;
  settings.spp = spp;
  settings.path.max_bounces = max_bounces;
  settings.path.rr_start = rr_start;
  const ReferenceResult r = render_reference(scene, *tracer, scene.camera, settings);
  EXPECT_EQ(r.nonfinite, 0u);
  return mean(r.image);
}

void expect_relative(vec3 actual, vec3 expected, float tolerance, const std::string& what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(actual[k], expected[k], tolerance * expected[k]) << what << " channel " << k;
}

TEST(PathFurnace, UnlimitedBouncesWithRussianRoulette) {
  const Scene s = furnace(kAlbedo, kRadiance);
  // Roulette from the first vertex on: the hardest case for its unbiasedness.
  expect_relative(reference_mean(s, -1, 0, 64), geometric_sum(kRadiance, kAlbedo, -1), 0.01f,
                  "rr_start 0");
  expect_relative(reference_mean(s, -1, 3, 64), geometric_sum(kRadiance, kAlbedo, -1), 0.01f,
                  "rr_start 3");
}

TEST(PathFurnace, MaxBouncesTruncatesTheSeriesWithAndWithoutRoulette) {
  const Scene s = furnace(kAlbedo, kRadiance);
  for (int bounces : {0, 1, 2, 5}) {
    // The camera sees Le (a^0) plus light with 0..B bounces: a^1 .. a^(B+1).
    const vec3 expected = geometric_sum(kRadiance, kAlbedo, bounces + 1);
    for (int rr_start : {0, kMaxPathBounces})
      expect_relative(
          reference_mean(s, bounces, rr_start, 64), expected, 0.01f,
          "max_bounces " + std::to_string(bounces) + " rr_start " + std::to_string(rr_start));
  }
}

TEST(PathFurnace, PipelineDirectPlusPathIndirectIsTheFullAnswer) {
  const Scene s = furnace(kAlbedo, kRadiance);
  for (int bounces : {-1, 1}) {
    // 32x32 pixels and 64 frames: eight times the samples of 16x16 and 32, so a seed rarely
    // lands the direct mean outside 1%.
    render_test::Job job("path", 32, 32);
    job.params = {{"max_bounces", std::to_string(bounces)}, {"samples", "4"}};
    job.light_samples = 4;
    job.frames = 64;
    job.jitter = true;
    const render_test::Images images = render_test::render(s, job);
    const Image& direct = images.direct;
    const Image& indirect = images.indirect;
    // Direct stage: Le + a Le. Indirect: light that bounced at least once, a^2 Le and on.
    const vec3 full = geometric_sum(kRadiance, kAlbedo, bounces < 0 ? -1 : bounces + 1);
    const vec3 expected_direct = geometric_sum(kRadiance, kAlbedo, 1);
    expect_relative(mean(direct), expected_direct, 0.01f, "direct");
    expect_relative(mean(indirect), full - expected_direct, 0.02f,
                    "indirect, max_bounces " + std::to_string(bounces));
  }
}

TEST(PathFurnace, ZeroBouncesGivesNoIndirectLight) {
  const Scene s = furnace(kAlbedo, kRadiance);
  auto tracer = make_embree_tracer(s);
  auto technique = make_technique("path");
  technique->params().set("max_bounces", "0");
  Renderer renderer(s, *tracer, std::move(technique));
  FrameSettings settings;
  settings.width = settings.height = 8;
  const Frame& f = renderer.render(s.camera, settings);
  EXPECT_EQ(mean(f.indirect), vec3(0.0f));
}

}  // namespace
}  // namespace bounce
