// The environment light end to end. The uniform-sky furnace: under a sky of radiance L every
// white (albedo 1) Lambert surface shows L, whatever its shape, once light may bounce without
// limit; a convex object shows it from direct light alone, a cavity only with its indirect light.
// And a plane under a small map, whose direct light is a brute-force sum over the map's texels.
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "bounce/eval/render_image.h"
#include "bounce/render/renderer.h"
#include "bounce/techniques/path/path_tracer.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/tiled/tiled.h"
#include "render/render_test_util.h"
#include "scene/environment_test_util.h"
#include "techniques/path/path_test_util.h"

namespace bounce {
namespace {

constexpr int kSize = 24;
const vec3 kSky(0.5f, 1.0f, 1.5f);

// A faceted sphere beside a box open to the sky, both white, under a uniform sky.
Scene furnace_scene() {
  Scene s;
  s.source = "sky furnace";
  Material white;
  white.name = "white";
  white.albedo = vec3(1.0f);
  s.materials.push_back(white);
  s.meshes.push_back(scene_test::faceted_sphere("ball", vec3(-0.7f, 0.4f, 0.0f), 0.4f, 12, 24, 0));
  s.meshes.push_back(scene_test::open_box("box", vec3(0.5f, 0.0f, 0.0f), 0.8f, 0));
  s.lights.push_back(Light::environment(kSky));
  s.camera.position = vec3(0.1f, 1.6f, -1.6f);
  s.camera.look_at = vec3(0.0f, 0.2f, 0.0f);
  s.camera.vfov_deg = 60.0f;
  s.has_camera = true;
  s.finalize();
  return s;
}

// The largest relative error of any channel of the image's mean, and of any 4x4 block's mean.
struct FurnaceError {
  float mean = 0.0f;
  float block = 0.0f;
};
FurnaceError furnace_error(const Image& image, vec3 expected) {
  FurnaceError e;
  const vec3 m = mean(image);
  for (int c = 0; c < 3; ++c) e.mean = std::max(e.mean, std::abs(m[c] / expected[c] - 1.0f));
  for (int y = 0; y < image.height(); y += 4)
    for (int x = 0; x < image.width(); x += 4) {
      const vec3 b = mean(image, x, y, x + 4, y + 4);
      for (int c = 0; c < 3; ++c) e.block = std::max(e.block, std::abs(b[c] / expected[c] - 1.0f));
    }
  return e;
}

TEST(EnvironmentFurnace, PathReferenceShowsTheSkyEverywhere) {
  const Scene scene = furnace_scene();
  const Image image = render_test::path_reference(scene, kSize, kSize, 256);
  const FurnaceError e = furnace_error(image, kSky);
  EXPECT_LT(e.mean, 0.01f);
  EXPECT_LT(e.block, 0.05f);
}

TEST(EnvironmentFurnace, TiledShowsTheSkyEverywhereWithItsPhotons) {
  const Scene scene = furnace_scene();
  render_test::Job job("tiled", kSize, kSize);
  job.params = {{"photons", "20000"}};
  job.light_samples = 8;
  job.frames = 16;
  job.jitter = true;
  const render_test::Images images = render_test::render(scene, job);
  const FurnaceError tiled = furnace_error(images.color, kSky);
  // Direct light alone misses what the cavity's walls send each other: the photons' part.
  const FurnaceError direct = furnace_error(images.direct, kSky);
  RecordProperty("tiled_mean_error", std::to_string(tiled.mean));
  RecordProperty("direct_mean_error", std::to_string(direct.mean));
  EXPECT_LT(tiled.mean, 0.03f);
  EXPECT_LT(tiled.block, 0.15f);
  EXPECT_GT(direct.mean, 3.0f * tiled.mean);
  EXPECT_GT(direct.block, 0.25f);
  EXPECT_GT(max_component(mean(images.indirect)), 0.0f);
}

TEST(EnvironmentFurnace, VertexShowsTheSkyOnAverage) {
  const Scene scene = furnace_scene();
  render_test::Job job("vertex", kSize, kSize);
  job.light_samples = 8;
  job.frames = 8;
  job.jitter = true;
  const render_test::Images images = render_test::render(scene, job);
  const FurnaceError vertex = furnace_error(images.color, kSky);
  const FurnaceError direct = furnace_error(images.direct, kSky);
  RecordProperty("vertex_mean_error", std::to_string(vertex.mean));
  EXPECT_LT(vertex.mean, 0.05f);
  EXPECT_GT(direct.mean, 2.0f * vertex.mean);
}

// A grey plane facing up under a small map turned about +y; the camera sees only the plane.
Scene plane_under_map(std::shared_ptr<const EnvironmentMap> map, float rotation_deg) {
  Scene s;
  s.source = "plane under a map";
  Material grey;
  grey.albedo = vec3(0.5f);
  s.materials.push_back(grey);
  s.meshes.push_back(
      scene_test::quad_mesh("floor", vec3(-1, 0, -1), vec3(0, 0, 2), vec3(2, 0, 0), 0));
  s.lights.push_back(Light::environment(vec3(1.0f), rotation_deg));
  s.environment_map = std::move(map);
  s.camera.position = vec3(0.0f, 3.0f, 0.0f);
  s.camera.look_at = vec3(0.0f);
  s.camera.up = vec3(0.0f, 0.0f, 1.0f);
  s.camera.vfov_deg = 20.0f;
  s.has_camera = true;
  s.finalize();
  return s;
}

// albedo / pi times the integral of L cos over the upper hemisphere, summed exactly texel by
// texel on a fine grid of each texel's (u, v) area (the map is piecewise constant).
vec3 plane_radiance_brute_force(const Scene& scene) {
  const EnvironmentMapView map = scene.environment_map->view();
  const LightRecord& light = scene.lights[0];
  const int n = 32;  // sub-cells per texel side
  glm::dvec3 sum(0.0);
  for (int y = 0; y < map.height * n; ++y)
    for (int x = 0; x < map.width * n; ++x) {
      const vec2 uv((x + 0.5f) / float(map.width * n), (y + 0.5f) / float(map.height * n));
      const vec3 d = environment_from_map(light.rotation, environment_direction(uv));
      const double cos_theta = std::max(0.0f, d.y);
      const double solid_angle =
          2.0 * kPi * kPi * std::sin(uv.y * kPi) / (double(map.width) * n * double(map.height) * n);
      sum += glm::dvec3(environment_radiance(light, map, d)) * cos_theta * solid_angle;
    }
  return vec3(sum) * (0.5f / kPi);
}

TEST(EnvironmentMapLight, DirectLightOnAPlaneEqualsTheBruteForceIntegral) {
  auto map = std::make_shared<const EnvironmentMap>(
      EnvironmentMap::from_image(scene_test::synthetic_map(8, 4), "synthetic"));
  const Scene scene = plane_under_map(map, 30.0f);
  const vec3 expected = plane_radiance_brute_force(scene);
  render_test::Job job("direct", 8, 8);
  job.light_samples = 64;
  job.frames = 16;
  const vec3 direct = mean(render_test::render(scene, job).direct);
  // The path tracer's estimate with MIS (light samples and escaping BSDF rays) and no bounces.
  const vec3 path = mean(render_test::path_reference(scene, 8, 8, 256, 0, 0));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(direct[c], expected[c], 0.01f * expected[c]) << "direct, channel " << c;
    EXPECT_NEAR(path[c], expected[c], 0.01f * expected[c]) << "path, channel " << c;
  }
}

// The path tracer's three ways to find the map from a surface point (light samples, BSDF rays
// that escape, both weighted by MIS) agree: on a Lambert point with the brute-force integral,
// on a glossy one with each other.
TEST(EnvironmentMapLight, PathStrategiesAgree) {
  auto map = std::make_shared<const EnvironmentMap>(
      EnvironmentMap::from_image(scene_test::synthetic_map(8, 4), "synthetic"));
  const Scene scene = plane_under_map(map, -50.0f);
  const vec3 lambert = plane_radiance_brute_force(scene);
  auto tracer = make_embree_tracer(scene);
  const LightPicker lights = LightPicker::build(scene);
  const SceneData data = SceneData::from(scene);
  const PathScene ps = path_scene(data.view(), *tracer, lights);
  const vec3 wo = glm::normalize(vec3(0.3f, 1.0f, -0.4f));
  // A point on the plane (whose own face hides the lower hemisphere).
  SurfaceHit x;
  x.position = vec3(0.1f, 0.0f, 0.2f);
  x.normal = x.geometric_normal = vec3(0, 1, 0);
  x.albedo = vec3(0.5f);
  SurfaceHit glossy = x;
  glossy.albedo = vec3(0.2f);
  glossy.f0 = vec3(0.6f);
  glossy.roughness = 0.4f;
  const auto estimate = [&](const SurfaceHit& at, LightStrategy strategy) {
    PathSettings settings;
    settings.max_bounces = 0;
    settings.strategy = strategy;
    PathCounters counters;
    path_test::Estimate e;
    for (int i = 0; i < 100000; ++i) {
      Pcg32 rng = path_rng(1, uint32_t(i), uint32_t(strategy));
      e.add(reflected_radiance(ps, settings, at, wo, rng, counters));
    }
    return e;
  };
  const path_test::Estimate glossy_mis = estimate(glossy, LightStrategy::kMis);
  for (LightStrategy strategy :
       {LightStrategy::kMis, LightStrategy::kLightOnly, LightStrategy::kBsdfOnly}) {
    const path_test::Estimate e = estimate(x, strategy);
    const path_test::Estimate g = estimate(glossy, strategy);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(e.mean(c), lambert[c], 5.0 * e.standard_error(c) + 2e-3 * lambert[c])
          << "strategy " << int(strategy) << " channel " << c;
      const double error = std::hypot(g.standard_error(c), glossy_mis.standard_error(c));
      EXPECT_NEAR(g.mean(c), glossy_mis.mean(c), 5.0 * error + 2e-3 * glossy_mis.mean(c))
          << "glossy, strategy " << int(strategy) << " channel " << c;
    }
  }
}

// A glossy plane under the map: direct light samples the map by luminance and the BSDF by its
// lobe, weighted by MIS, so one sample per pixel has no fireflies (light sampling alone scatters
// a few pixels many times the mean), and many samples agree with the path tracer's estimate.
TEST(EnvironmentMapLight, GlossyDirectLightHasNoFireflies) {
  auto map = std::make_shared<const EnvironmentMap>(
      EnvironmentMap::from_image(scene_test::synthetic_map(8, 4), "synthetic"));
  Scene scene = plane_under_map(map, 30.0f);
  scene.materials[0].albedo = vec3(0.05f);
  scene.materials[0].f0 = vec3(0.9f);
  scene.materials[0].roughness = 0.1f;
  scene.finalize();
  render_test::Job one("direct", 16, 16);
  one.light_samples = 1;
  const Image frame = render_test::render(scene, one).direct;
  const auto grey = [](vec3 c) { return c.x + c.y + c.z; };
  const float m = grey(mean(frame));
  float worst = 0.0f;
  for (const vec3& p : frame.pixels()) worst = std::max(worst, grey(p) / m);
  EXPECT_LT(worst, 2.0f) << "brightest pixel / mean";

  render_test::Job many("direct", 8, 8);
  many.light_samples = 64;
  many.frames = 16;
  const vec3 direct = mean(render_test::render(scene, many).direct);
  const vec3 path = mean(render_test::path_reference(scene, 8, 8, 1024, 0, 0));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(direct[c], path[c], 0.02f * path[c]) << "channel " << c;
}

TEST(EnvironmentMapLight, RaysThatLeaveTheSceneSeeTheMap) {
  Image image(4, 2);
  for (int i = 0; i < 8; ++i) image.pixels()[size_t(i)] = vec3(float(i + 1), 1.0f, 0.5f);
  auto map = std::make_shared<const EnvironmentMap>(EnvironmentMap::from_image(image, "8 texels"));
  Scene scene = plane_under_map(map, 0.0f);
  // Look from above the plane into the middle of texel (1, 0), away from every texel border.
  const vec3 d = environment_direction(vec2(0.375f, 0.25f));
  scene.camera.position = vec3(0.0f, 0.5f, 0.0f);
  scene.camera.look_at = scene.camera.position + d;
  scene.camera.up = vec3(0.0f, 1.0f, 0.0f);
  scene.camera.vfov_deg = 1.0f;
  render_test::Job job("direct", 2, 2);
  const Image seen = render_test::render(scene, job).color;
  const vec3 expected(2.0f, 1.0f, 0.5f);
  EXPECT_EQ(environment_radiance(scene.lights[0], map->view(), d), expected);
  for (const vec3& p : seen.pixels())
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 1e-4f);
  const Image reference = render_test::path_reference(scene, 2, 2, 4);
  for (const vec3& p : reference.pixels())
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 1e-4f);
}

}  // namespace
}  // namespace bounce
