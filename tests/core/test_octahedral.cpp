#include <gtest/gtest.h>

#include "bounce/core/octahedral.h"
#include "bounce/core/qmc.h"
#include "bounce/core/sampling.h"

namespace bounce {
namespace {

TEST(Octahedral, RoundTripsEveryDirectionWithinQuantisation) {
  float worst = 0.0f;
  for (uint32_t i = 0; i < 100000; ++i) {
    const vec3 v = sample_uniform_sphere(sobol2(i));
    const vec3 exact = oct_decode(oct_encode(v));
    EXPECT_NEAR(glm::length(exact - v), 0.0f, 1e-5f);
    worst = std::max(worst, glm::length(oct_unpack(oct_pack(v)) - v));
  }
  // 16-bit components: errors of a few 1e-5 radians at most.
  EXPECT_LT(worst, 1e-4f);
  for (vec3 axis : {vec3(1, 0, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)})
    EXPECT_NEAR(glm::length(oct_unpack(oct_pack(axis)) - axis), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace bounce
