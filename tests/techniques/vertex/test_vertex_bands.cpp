// Technique `vertex` locates each pixel's refined triangle band by band inside the renderer's
// G-buffer pass (Technique::begin_gbuffer_bands): the indirect light must be what indirect()
// gives when it locates every pixel itself, into an image it is not given zeroed.
#include <gtest/gtest.h>

#include <limits>

#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "vertex_test_util.h"

namespace bounce {
namespace {

using vertex_test::VertexRun;

TEST(VertexBands, LocatingInTheGBufferPassChangesNothing) {
  const Scene scene = make_cornell();
  VertexRun run(scene, {{"mesh_refinement", "2000"}}, 40);
  run.settings.width = 53;  // bands cut at the bottom, rows not a multiple of anything
  run.settings.height = 37;
  const Frame& f = run.frame(scene);
  const Image banded = f.indirect;
  EXPECT_GT(f.times.get("indirect/locate"), 0.0);

  // The same frame's indirect light with every pixel located by indirect() itself.
  const SceneData data = SceneData::from(scene);
  const CameraRays rays = CameraRays::from(scene.camera, f.gbuffer.width, f.gbuffer.height);
  const SceneChange none;
  StageTimes times;
  TechniqueCounters counters;
  const FrameContext context{scene, data.view(), *run.tracer, f.gbuffer, rays,
                             none,  false,       1,           times,     counters};
  // The technique assigns every pixel (indirect_overwrites): the renderer does not zero the
  // image first, so whatever it held must not show through.
  ASSERT_TRUE(run.technique->indirect_overwrites());
  Image alone(f.gbuffer.width, f.gbuffer.height);
  for (vec3& p : alone.pixels()) p = vec3(std::numeric_limits<float>::quiet_NaN());
  run.technique->indirect(context, alone);
  EXPECT_GT(times.get("indirect/locate"), 0.0);
  double sum = 0.0;
  for (size_t i = 0; i < alone.pixel_count(); ++i) {
    EXPECT_EQ(banded.pixels()[i], alone.pixels()[i]) << i;
    sum += alone.pixels()[i].x;
  }
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace bounce
