// Photons from the environment light: they leave a disc of the scene's bounding radius across
// each sampled direction, and their flux adds up to the light's power (the flux through that
// disc), for a sky colour and for a map.
#include <memory>

#include <gtest/gtest.h>

#include "bounce/core/qmc.h"
#include "bounce/core/rng.h"
#include "bounce/render/photon_emission.h"
#include "bounce/scene/scene_data.h"
#include "scene/environment_test_util.h"

namespace bounce {
namespace {

Scene box_under_sky(std::shared_ptr<const EnvironmentMap> map) {
  Scene s;
  s.source = "box under the sky";
  s.materials.push_back(Material{});
  s.meshes.push_back(scene_test::open_box("box", vec3(1.0f, 0.0f, 2.0f), 0.8f, 0));
  s.lights.push_back(Light::environment(vec3(0.5f, 1.0f, 2.0f), 40.0f));
  s.environment_map = std::move(map);
  s.finalize();
  return s;
}

TEST(EnvironmentPhotons, FluxAddsUpToThePowerThroughTheDisc) {
  auto map = std::make_shared<const EnvironmentMap>(
      EnvironmentMap::from_image(scene_test::synthetic_map(16, 8), "synthetic"));
  for (const bool with_map : {false, true}) {
    const Scene scene = box_under_sky(with_map ? map : nullptr);
    const SceneData data = SceneData::from(scene);
    const PhotonEmitters emitters = PhotonEmitters::from(scene);
    const vec3 power = scene.lights[0].power(emitters.scene_radius);
    // pi r^2 times the radiance integrated over the sphere.
    const vec3 mean = with_map ? map->mean() : vec3(1.0f);
    const float r = emitters.scene_radius;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(power[c], scene.lights[0].radiance[c] * mean[c] * 4.0f * kPi * kPi * r * r,
                  1e-4f * power[c]);

    const uint32_t n = 200000;
    Pcg32 rng(9, 2);
    glm::dvec3 total(0.0);
    int empty = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const EmittedPhoton p =
          emit_photon(data.view(), emitters.view(), hammersley(i, n), rng.next2(), n);
      total += glm::dvec3(p.flux);
      // A direction exactly at a pole (u = 0: the first Hammersley point) has no pdf: such a
      // photon carries nothing.
      if (max_component(p.flux) == 0.0f) {
        ++empty;
        continue;
      }
      // The photon starts 2r before the centre along its direction, within r of the line
      // through the centre: its disc covers the bounding sphere.
      const vec3 to_centre = emitters.scene_centre - p.origin;
      const float along = glm::dot(to_centre, p.direction);
      ASSERT_NEAR(along, 2.0f * r, 1e-3f * r) << i;
      ASSERT_LE(glm::length(to_centre - along * p.direction), r * (1.0f + 1e-4f)) << i;
    }
    EXPECT_LE(empty, 1);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(total[c], power[c], 0.01 * power[c]) << (with_map ? "map" : "sky") << " " << c;
  }
}

}  // namespace
}  // namespace bounce
