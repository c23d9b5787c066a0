// keep_unchanged: while a frame's photons equal the ones they replace, `vertex` keeps its kd-tree
// and the estimates it made, and the frames are the ones it would have computed again.
#include <gtest/gtest.h>

#include <algorithm>

#include "bounce/interactive/flashlight.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_edit.h"
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
    // ... and those paths are not traced at all: the slot keeps the photons it holds.
    EXPECT_EQ(keep.technique->reused_still_photons(), f >= 3);
    EXPECT_FALSE(recompute.technique->reused_still_photons());
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
  EXPECT_FALSE(run.technique->reused_still_photons());
  EXPECT_GT(run.technique->estimates(), 0u);
  // The tree holds the dimmed slot beside the old ones: not the map it kept. The slots traced
  // before the change are traced again, however still the scene is since.
  for (int f = 0; f < 2; ++f) {
    run.frame(scene);
    EXPECT_FALSE(run.technique->kept_tree());
    EXPECT_FALSE(run.technique->reused_still_photons());
  }
  run.frame(scene);
  EXPECT_TRUE(run.technique->reused_still_photons());
}

// A mesh that moves once and stops: the slots traced before it moved hold photons of the old
// geometry, so they are traced again as the ring turns, and kept only from then on; every frame
// is the one retracing every photon gives.
TEST(VertexKeep, StillPhotonsAreKeptOnlyIfTracedSinceTheLastChange) {
  Scene scene = make_cornell();
  VertexRun keep(scene, kSmall, 24), recompute(scene, with(kSmall, "keep_unchanged", "false"), 24);
  for (VertexRun* run : {&keep, &recompute}) run->settings.accumulate = false;
  const uint32_t moved = uint32_t(scene.meshes.size() - 1);
  for (int f = 0; f < 12; ++f) {
    SCOPED_TRACE(f);
    if (f == 5) {
      const SceneChange change = move_mesh(scene, moved, vec3(0.05f, 0.0f, 0.0f));
      keep.renderer->scene_changed(change);
      recompute.renderer->scene_changed(change);
    }
    const Frame& a = keep.frame(scene);
    const Frame& b = recompute.frame(scene);
    ASSERT_EQ(a.indirect.pixels(), b.indirect.pixels());
    // The 3 slots fill in frames 0-2; frame 5 moves the mesh, and frames 6 and 7 refill slots
    // traced before it did.
    EXPECT_EQ(keep.technique->reused_still_photons(), (f >= 3 && f < 5) || f >= 8);
  }
}

// At rest with accumulation each frame's photons are a fresh set, not the slot's frame-coherent
// one: when the camera moves again, those slots are traced again.
TEST(VertexKeep, FreshSetsAtRestAreNotKeptAsFrameCoherentOnes) {
  Scene scene = make_cornell();
  VertexRun run(scene, kSmall, 24);
  run.settings.accumulate = true;
  for (int f = 0; f < 6; ++f) {
    run.frame(scene);
    EXPECT_FALSE(run.technique->reused_still_photons()) << f;
  }
  Camera camera = scene.camera;
  for (int f = 0; f < 3; ++f) {
    camera.position.x += 0.01f;
    run.renderer->render(camera, run.settings);
    EXPECT_FALSE(run.technique->reused_still_photons()) << f;
  }
  camera.position.x += 0.01f;
  run.renderer->render(camera, run.settings);
  EXPECT_TRUE(run.technique->reused_still_photons());
}

// A light that moves every frame (a flashlight swept across the box) keeps its photons apart:
// once the ring holds only slots traced since it began to move, the tree of the other light's
// photons stands while the moving light's is rebuilt, and the frames are those of one tree
// rebuilt over all the photons each frame (equal to rounding: the sums run in another order).
TEST(VertexKeep, AMovingLightLeavesTheOtherLightsTreeStanding) {
  Scene scene = make_cornell();
  FlashlightSettings flashlight;
  flashlight.intensity = vec3(2.0f);
  const size_t index = add_flashlight(scene, scene.camera, flashlight);
  VertexRun keep(scene, kSmall, 24), rebuild(scene, with(kSmall, "keep_unchanged", "false"), 24);
  for (VertexRun* run : {&keep, &rebuild}) run->settings.accumulate = false;
  for (int f = 0; f < 8; ++f) {
    SCOPED_TRACE(f);
    Camera held = scene.camera;
    held.look_at += vec3(0.04f * float(f), 0.0f, 0.0f);
    if (place_flashlight(scene, index, held, flashlight)) {
      SceneChange moved;
      moved.lights = true;
      keep.renderer->scene_changed(moved);
      rebuild.renderer->scene_changed(moved);
    }
    const Image a = keep.frame(scene).indirect;
    const Image b = rebuild.frame(scene).indirect;
    ASSERT_EQ(a.pixel_count(), b.pixel_count());
    float worst = 0.0f, brightest = 0.0f;
    for (size_t i = 0; i < a.pixel_count(); ++i) {
      worst = std::max(worst, max_component(glm::abs(a.pixels()[i] - b.pixels()[i])));
      brightest = std::max(brightest, max_component(b.pixels()[i]));
    }
    ASSERT_GT(brightest, 0.0f);
    EXPECT_LE(worst, 1e-5f * brightest);
    EXPECT_FALSE(rebuild.technique->kept_tree());
    EXPECT_EQ(rebuild.technique->moving_ring().photon_count(), 0u);
    // Frame 1 moves the light; frame 3 still replaces frame 0's slot, which held its photons.
    EXPECT_EQ(keep.technique->kept_tree(), f >= 4);
    // The other light's paths are kept from then on, the moving light's traced every frame.
    EXPECT_EQ(keep.technique->reused_still_photons(), f >= 4);
    if (f >= 1) {
      EXPECT_FALSE(keep.technique->kept_moving_tree());
      EXPECT_GT(keep.technique->moving_ring().photon_count(), 0u);
    }
  }
}

}  // namespace
}  // namespace bounce
