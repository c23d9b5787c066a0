#include <gtest/gtest.h>

#include "bounce/core/error.h"
#include "bounce/render/params.h"

namespace bounce {
namespace {

TEST(Params, SetsValuesByNameWithChecks) {
  float radius = 1.0f;
  int photons = 1000;
  bool progressive = false;
  ParamSet set;
  set.add_float("radius", &radius, 0.0, 10.0, "gather radius");
  set.add_int("photons", &photons, 1, 1000000, "photon paths");
  set.add_bool("progressive", &progressive, "refine at rest");
  set.set_assignment("radius=2.5");
  set.set("photons", "5000");
  set.set("progressive", "true");
  EXPECT_EQ(radius, 2.5f);
  EXPECT_EQ(photons, 5000);
  EXPECT_TRUE(progressive);
  EXPECT_EQ(set.find("photons")->to_string(), "5000");
  EXPECT_THROW(set.set("radius", "11"), Error);
  EXPECT_THROW(set.set("radius", "abc"), Error);
  EXPECT_THROW(set.set("photons", "1.5"), Error);
  EXPECT_THROW(set.set("progressive", "maybe"), Error);
  EXPECT_THROW(set.set_assignment("radius"), Error);
  try {
    set.set("radiuss", "1");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("radiuss"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("radius, photons, progressive"), std::string::npos);
  }
  EXPECT_EQ(radius, 2.5f);  // failed sets leave values alone
}

}  // namespace
}  // namespace bounce
