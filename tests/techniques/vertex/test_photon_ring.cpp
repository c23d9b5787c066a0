// The ring of accumulation frames: each frame refills the oldest slot, so a frame's photons are
// gone after accumulation_frames further frames.
#include <gtest/gtest.h>

#include "bounce/techniques/vertex/photon_ring.h"

namespace bounce {
namespace {

TEST(PhotonRing, PhotonsAgeOutAfterAccumulationFrames) {
  PhotonRing ring;
  ring.reset(3);
  for (uint32_t frame = 0; frame < 7; ++frame) {
    MapPhotons& slot = ring.begin_frame(frame);
    // Frame f stores f + 1 photons whose flux names the frame.
    for (uint32_t k = 0; k <= frame; ++k) {
      slot.position.push_back(vec3(float(k)));
      slot.flux.push_back(vec3(float(frame)));
      slot.normal.push_back(vec3(0, 1, 0));
    }
    EXPECT_EQ(ring.filled(), std::min(frame + 1, 3u));
    MapPhotons all;
    ring.gather(all);
    // Held: the last min(frame + 1, 3) frames, and nothing older.
    size_t expected = 0;
    for (uint32_t f = frame >= 2 ? frame - 2 : 0; f <= frame; ++f) expected += f + 1;
    EXPECT_EQ(all.size(), expected) << "frame " << frame;
    for (const vec3& flux : all.flux) {
      EXPECT_LE(flux.x, float(frame));
      EXPECT_GE(flux.x + 2.0f, float(frame)) << "a photon older than the ring at frame " << frame;
    }
  }
  ring.reset(2);
  EXPECT_EQ(ring.filled(), 0u);
  EXPECT_EQ(ring.photon_count(), 0u);
}

}  // namespace
}  // namespace bounce
