// keep_unchanged: while a frame's photons equal the ones they replace, `vertex` keeps its kd-tree
// and the estimates it made, and the frames are the ones it would have computed again.
#include <gtest/gtest.h>

#include "bounce/scene/load.h"
#include "vertex_test_util.h"

namespace bounce {
namespace {

using vertex_test::VertexRun;

const std::vector<std::pair<std::string, std::string>> kSmall = {
    {"accumulation_frames", "3"}, {"photons_from_light", "40"}, {"mesh_refinement", "300"}};

std::vector<std::pair<std::string, std::string>> with(
    std::vector<std::pair<std::string, std::string>> params, const char* name, const char* value) {
  params.emplace_back(name, value);
  return params;
}

TEST(VertexKeep, AStillSceneKeepsItsTreeAndEstimatesAndTheSameFrames) {
  Scene scene = make_cornell();
  VertexRun keep(scene, kSmall, 24), recompute(scene, with(kSmall, "keep_unchanged", "false"), 24);
  for (VertexRun* run : {&keep, &recompute}) run->settings.accumulate = false;
  for (int f = 0; f < 8; ++f) {
    SCOPED_TRACE(f);
    const Frame& a = keep.frame(scene);
    const Frame& b = recompute.frame(scene);
    ASSERT_EQ(a.indirect.pixels(), b.indirect.pixels());
    EXPECT_FALSE(recompute.technique->kept_tree());
    // The ring fills in 3 frames; from then on each refill retraces the paths it replaces.
    EXPECT_EQ(keep.technique->kept_tree(), f >= 3);
    EXPECT_GT(recompute.technique->estimates(), 0u);
    if (f >= 3) {
      EXPECT_EQ(keep.technique->estimates(), 0u) << "every visible key was estimated already";
    } else {
      EXPECT_EQ(keep.technique->estimates(), recompute.technique->estimates());
    }
  }
}

TEST(VertexKeep, ADimmedLightMakesNewPhotonsAndANewTree) {
  Scene scene = make_cornell();
  VertexRun run(scene, kSmall, 24);
  run.settings.accumulate = false;
  for (int f = 0; f < 5; ++f) run.frame(scene);
  ASSERT_TRUE(run.technique->kept_tree());
  for (Material& m : scene.materials)
    if (max_component(m.emission) > 0.0f) m.emission *= 0.5f;
  scene.derive();
  SceneChange change;
  change.materials = true;
  run.renderer->scene_changed(change);
  run.frame(scene);
  EXPECT_FALSE(run.technique->kept_tree());
  EXPECT_GT(run.technique->estimates(), 0u);
  // The tree holds the dimmed slot beside the old ones: not the map it kept.
  run.frame(scene);
  EXPECT_FALSE(run.technique->kept_tree());
}

}  // namespace
}  // namespace bounce
