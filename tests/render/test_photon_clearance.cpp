#include <gtest/gtest.h>

#include <cmath>

#include "bounce/render/photon_clearance.h"

namespace bounce {
namespace {

// The comparison-based sector lookup agrees with the angle it stands for.
TEST(PhotonClearance, SectorOfEveryDirectionMatchesItsAngle) {
  const vec3 n(0.0f, 0.0f, 1.0f);
  const Basis frame = Basis::from_normal(n);
  for (int sector = 0; sector < kClearanceRays; ++sector) {
    for (float within : {0.1f, 0.5f, 0.9f}) {
      const float angle = kTwoPi * (float(sector) + within) / float(kClearanceRays);
      const vec3 x = std::cos(angle) * frame.t + std::sin(angle) * frame.b;  // distance 1
      // Only this sector's two bounding rays are short: x is rejected...
      float clearance[kClearanceRays];
      for (float& c : clearance) c = 10.0f;
      clearance[(sector + 1) % kClearanceRays] = 0.5f;
      EXPECT_FALSE(within_clearance(x, vec3(0.0f), n, clearance)) << sector << " " << within;
      // ...and with every other ray short but these two long, it is accepted.
      for (float& c : clearance) c = 0.5f;
      clearance[sector] = clearance[(sector + 1) % kClearanceRays] = 10.0f;
      EXPECT_TRUE(within_clearance(x, vec3(0.0f), n, clearance)) << sector << " " << within;
    }
  }
}

}  // namespace
}  // namespace bounce
