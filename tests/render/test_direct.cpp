// Direct light against analytic irradiance: a white Lambertian square (albedo 1) reflects
// radiance E / pi, so the pixel at the square's centre measures the irradiance there.
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/eval/render_image.h"
#include "bounce/render/renderer.h"
#include "bounce/techniques/registry.h"
#include "render/render_test_util.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

constexpr int kSize = 31;  // odd: the centre pixel's centre is the square's centre

using scene_test::quad_mesh;

// A 4 x 4 m white square in the plane y = 0 seen from above by a narrow camera.
Scene lit_square() {
  Scene s;
  s.source = "square";
  Material white;
  white.albedo = vec3(1.0f);
  s.materials.push_back(white);
  s.meshes.push_back(quad_mesh("floor", vec3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), 0));
  s.camera.position = vec3(0.0f, 3.0f, 0.0f);
  s.camera.look_at = vec3(0.0f);
  s.camera.up = vec3(0.0f, 0.0f, 1.0f);
  s.camera.vfov_deg = 10.0f;
  s.has_camera = true;
  return s;
}

float centre_irradiance(Scene scene, int light_samples = 64) {
  scene.finalize();
  render_test::Job job("direct", kSize, kSize);
  job.light_samples = light_samples;
  const Image image = render_test::render(scene, job).color;
  return kPi * image.at(kSize / 2, kSize / 2).y;
}

TEST(DirectLight, PointLightGivesInverseSquareIrradiance) {
  for (float h : {0.5f, 1.0f, 2.0f}) {
    Scene s = lit_square();
    s.lights.push_back(Light::point(vec3(0.0f, h, 0.0f), vec3(2.0f)));
    EXPECT_NEAR(centre_irradiance(s), 2.0f / (h * h), 0.01f * 2.0f / (h * h)) << h;
  }
}

TEST(DirectLight, OccluderCastsAShadow) {
  Scene s = lit_square();
  s.lights.push_back(Light::point(vec3(0.0f, 1.0f, 0.0f), vec3(2.0f)));
  s.materials.push_back(Material{});
  // A small blocker halfway between the light and the square's centre; the camera looks at the
  // centre at a slant so that it sees past the blocker.
  s.meshes.push_back(
      quad_mesh("blocker", vec3(-0.05f, 0.5f, -0.05f), vec3(0.1f, 0, 0), vec3(0, 0, 0.1f), 1));
  s.camera.position = vec3(0.0f, 1.0f, -2.0f);
  s.camera.up = vec3(0, 1, 0);
  EXPECT_NEAR(centre_irradiance(s), 0.0f, 1e-6f);
}

TEST(DirectLight, SpotAndDirectionalLights) {
  Scene spot = lit_square();
  spot.lights.push_back(Light::spot(vec3(0, 1, 0), vec3(0, -1, 0), vec3(3.0f), 10.0f, 20.0f));
  EXPECT_NEAR(centre_irradiance(spot), 3.0f, 0.03f);
  Scene away = lit_square();
  away.lights.push_back(Light::spot(vec3(0, 1, 0), vec3(1, -0.2f, 0), vec3(3.0f), 10.0f, 20.0f));
  EXPECT_NEAR(centre_irradiance(away), 0.0f, 1e-6f);
  Scene sun = lit_square();
  const vec3 dir = glm::normalize(vec3(1.0f, -2.0f, 0.0f));
  sun.lights.push_back(Light::directional(dir, vec3(5.0f)));
  EXPECT_NEAR(centre_irradiance(sun), 5.0f * -dir.y, 0.01f * 5.0f);
}

TEST(DirectLight, SphereLightMatchesAnalyticIrradiance) {
  // A sphere of radiance L and radius R at distance d above: E = pi L (R / d)^2.
  Scene s = lit_square();
  const float radiance = 10.0f, radius = 0.2f, d = 1.0f;
  s.lights.push_back(Light::sphere(vec3(0.0f, d, 0.0f), radius, vec3(radiance)));
  s.camera.position = vec3(0.0f, 0.5f, -2.0f);  // below the light: the light is in view otherwise
  s.camera.up = vec3(0, 1, 0);
  const float expected = kPi * radiance * radius * radius / (d * d);
  EXPECT_NEAR(centre_irradiance(s, 256), expected, 0.01f * expected);
}

// Irradiance at a point below the corner of a parallel a x b rectangle of radiance L at height c
// (the classical differential-area-to-rectangle view factor, times pi L).
double corner_rectangle_irradiance(double a, double b, double c, double radiance) {
  const double x = a / c, y = b / c;
  const double f = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                    y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                   (2.0 * kPi);
  return kPi * radiance * f;
}

TEST(DirectLight, EmissiveQuadMatchesAnalyticIrradianceAndIsOneSided) {
  const float side = 0.5f, h = 0.6f, radiance = 4.0f;
  Material emitter;
  emitter.albedo = vec3(0.0f);
  emitter.emission = vec3(radiance);
  Scene down = lit_square();
  down.materials.push_back(emitter);
  // Winding chosen so the face normal points down (-y), towards the square.
  down.meshes.push_back(
      quad_mesh("light", vec3(-side / 2, h, -side / 2), vec3(side, 0, 0), vec3(0, 0, side), 1));
  down.camera.position = vec3(0.0f, 0.3f, -0.5f);  // below the light, looking at the centre
  down.camera.up = vec3(0, 1, 0);
  const double expected = 4.0 * corner_rectangle_irradiance(side / 2, side / 2, h, radiance);
  EXPECT_NEAR(centre_irradiance(down, 256), expected, 0.01 * expected);

  Scene up = down;
  std::swap(up.meshes[1].triangles[0].y, up.meshes[1].triangles[0].z);
  std::swap(up.meshes[1].triangles[1].y, up.meshes[1].triangles[1].z);
  EXPECT_NEAR(centre_irradiance(up), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace bounce

namespace bounce {
namespace {

TEST(DirectLight, SphereLightSeenDirectlyShowsItsRadiance) {
  Scene s = lit_square();
  s.lights.push_back(Light::sphere(vec3(0.0f, 1.0f, 0.0f), 0.1f, vec3(7.0f, 5.0f, 3.0f)));
  s.finalize();
  auto tracer = make_embree_tracer(s);
  Renderer renderer(s, *tracer, make_technique("direct"));
  FrameSettings settings;
  settings.width = settings.height = kSize;
  settings.light_samples = 4;
  const Frame& f = renderer.render(s.camera, settings);
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
  EXPECT_EQ(f.color.pixels()[centre], vec3(7.0f, 5.0f, 3.0f));
  EXPECT_FALSE(f.gbuffer.hit(centre));
  EXPECT_NEAR(f.gbuffer.depth[centre], 3.0f - 1.0f - 0.1f, 1e-4f);  // camera 3 m above the floor
  // A corner pixel sees the lit floor, not the light.
  EXPECT_TRUE(f.gbuffer.hit(0));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(f.color.pixels()[0][c], 0.0f) << c;
    EXPECT_LT(f.color.pixels()[0][c], vec3(7.0f, 5.0f, 3.0f)[c]) << c;
  }
}

}  // namespace
}  // namespace bounce
