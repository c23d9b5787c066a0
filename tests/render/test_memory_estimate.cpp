// The techniques' memory estimates (render/memory_estimate.h): analytic photon counts per path,
// and estimates that follow the parameters that size what is kept.
#include <gtest/gtest.h>

#include <cstdint>

#include "bounce/render/memory_estimate.h"
#include "bounce/render/photon_path.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/lhb/lhb.h"
#include "bounce/techniques/tiled/tiled.h"
#include "bounce/techniques/vertex/vertex.h"

namespace bounce {
namespace {

Scene scene_with_albedo(vec3 albedo) {
  Scene scene = load_scene("cornell");
  for (Material& m : scene.materials) m.albedo = albedo;
  return scene;
}

TEST(MemoryEstimate, RussianRouletteDepositsFollowTheLargestAlbedo) {
  // Survival a at each hit, a deposit at every hit after the first: a + a^2 + ... = a / (1 - a).
  EXPECT_DOUBLE_EQ(expected_photon_deposits(scene_with_albedo(vec3(0.5f)), -1), 1.0);
  EXPECT_NEAR(expected_photon_deposits(scene_with_albedo(vec3(0.1f, 0.75f, 0.2f)), -1), 3.0, 1e-6);
  // A white room never ends a path by roulette: the depth cap holds.
  EXPECT_DOUBLE_EQ(expected_photon_deposits(scene_with_albedo(vec3(1.0f)), -1),
                   double(kMaxPhotonDepth));
  // A fixed bounce count deposits at most that many.
  EXPECT_DOUBLE_EQ(expected_photon_deposits(scene_with_albedo(vec3(0.5f)), 3), 3.0);
  EXPECT_DOUBLE_EQ(expected_photon_deposits(scene_with_albedo(vec3(0.5f)), 0), 0.0);
}

TEST(MemoryEstimate, TiledCountsEveryPhotonOfEveryHeldPass) {
  const Scene scene = scene_with_albedo(vec3(0.5f));
  TiledPhotonMapping tiled;
  tiled.settings().photons = 1000;
  tiled.settings().history_passes = 4;
  tiled.settings().bounces = -1;
  // 1000 paths x 4 passes x 1 deposit x 64 bytes, held and gathered again: 512,000 bytes.
  EXPECT_EQ(tiled.memory_estimate(scene), 512000u);
  tiled.settings().history_passes = 8;
  EXPECT_EQ(tiled.memory_estimate(scene), 1024000u);
}

TEST(MemoryEstimate, VertexCountsTheSplitTreeAndTheRefinement) {
  const Scene scene = scene_with_albedo(vec3(0.5f));
  VertexPhotonMapping vertex;
  VertexSettings& s = vertex.settings();
  s.photons_from_light = 10;
  s.accumulation_frames = 2;
  s.diffuse_reflections = 4;
  s.recursion_depth = 2;
  s.mesh_refinement = 0;
  // Per path 1 + 4 + 16 photons, and the 16 of the last level go on with 1 deposit each: 37.
  // 10 x 2 x 37 photons x 36 bytes x 3 copies = 79,920 bytes, and keep_unchanged's copy of one
  // slot: 10 x 37 x 36 = 13,320.
  EXPECT_EQ(vertex.memory_estimate(scene), 79920u + 13320u);
  s.keep_unchanged = false;
  EXPECT_EQ(vertex.memory_estimate(scene), 79920u);
  s.mesh_refinement = 1000;
  EXPECT_EQ(vertex.memory_estimate(scene), 79920u + 350000u);
  // An absurd split count saturates instead of wrapping.
  s.diffuse_reflections = 1 << 30;
  s.recursion_depth = 4;
  s.photons_from_light = 10000000;
  EXPECT_GT(vertex.memory_estimate(scene), uint64_t(1) << 60);
}

TEST(MemoryEstimate, LhbCountsItsHitBuffers) {
  const Scene scene = load_scene("cornell");
  LhbTechnique lhb;
  LhbTechniqueSettings& s = lhb.settings();
  s.directions = 320;
  s.size = 128;
  s.layers = 16;
  // 320 directions x 128^2 texels x (16 elements of 8 bytes + a count byte).
  EXPECT_EQ(lhb.memory_estimate(scene), uint64_t(320) * 128 * 128 * (16 * 8 + 1));
}

}  // namespace
}  // namespace bounce
