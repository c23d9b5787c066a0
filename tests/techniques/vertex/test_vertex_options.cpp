// Every one of the seed's switches gives a frame of the same light: each option on the Cornell
// box, against the defaults' mean indirect radiance (a 16x16 frame at rest, 4 frames).
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/scene/load.h"
#include "tests/techniques/vertex/vertex_test_util.h"

namespace bounce {
namespace {

using vertex_test::VertexRun;
using Params = std::vector<std::pair<std::string, std::string>>;

double mean_indirect(const Params& extra, uint64_t* stored = nullptr) {
  const Scene scene = make_cornell();
  Params params = {{"photons_from_light", "300"}, {"mesh_refinement", "3000"}};
  params.insert(params.end(), extra.begin(), extra.end());
  VertexRun run(scene, params, 16);
  run.settings.accumulate = true;
  const Frame* f = nullptr;
  for (int k = 0; k < 4; ++k) f = &run.frame(scene);
  if (stored) *stored = run.technique->photon_count();
  double sum = 0.0;
  for (size_t i = 0; i < f->indirect.pixel_count(); ++i) {
    const vec3 p = f->indirect.pixels()[i];
    EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    sum += p.x + p.y + p.z;
  }
  return sum / double(f->indirect.pixel_count());
}

TEST(VertexOptions, EverySeedSwitchKeepsTheLight) {
  uint64_t base_photons = 0;
  const double base = mean_indirect({}, &base_photons);
  ASSERT_GT(base, 0.0);
  const std::vector<std::pair<Params, double>> cases = {
      {{{"BSP_tree", "false"}}, 0.02},  // the same rays, tested against every triangle
      {{{"light_distribution_type", "1"}}, 0.15},
      {{{"diffuse_light_distribution", "1"}}, 0.15},
      {{{"snowball_size", "4"}}, 0.15},
      {{{"use_radius_heuristic", "true"}}, 0.25},
      {{{"recursion_depth", "2"}, {"diffuse_reflections", "9"}}, 0.15},
      {{{"final_gathering", "true"}, {"final_gathering_samples", "16"}}, 0.25},
  };
  for (const auto& [params, tolerance] : cases) {
    const double m = mean_indirect(params);
    EXPECT_NEAR(m, base, tolerance * base) << params[0].first;
  }
  // store_direct_light adds the first hits to the map: much more light in the indirect image.
  uint64_t with_direct = 0;
  EXPECT_GT(mean_indirect({{"store_direct_light", "true"}}, &with_direct), 1.5 * base);
  EXPECT_GT(with_direct, base_photons);
}

}  // namespace
}  // namespace bounce
