// The path tracer's sampling: the BSDF sampler against its own pdf and against quadrature, the
// light picker, and the three light strategies (MIS, light only, BSDF only) against each other
// and against analytic answers.
#include <gtest/gtest.h>

#include "bounce/core/qmc.h"
#include "bounce/render/bsdf_sampling.h"
#include "bounce/render/light_pdf.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/light_sampling.h"
#include "bounce/scene/scene_data.h"
#include "bounce/techniques/path/path_tracer.h"
#include "path_test_util.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

using path_test::Estimate;

struct TestMaterial {
  vec3 albedo;
  float roughness;
  vec3 f0;
};
const TestMaterial kMaterials[] = {
    {vec3(0.8f, 0.5f, 0.2f), 1.0f, vec3(0.0f)},   // Lambert only
    {vec3(0.5f), 0.6f, vec3(0.04f)},              // rough dielectric
    {vec3(0.3f, 0.4f, 0.5f), 0.2f, vec3(0.5f)},   // glossy
    {vec3(0.0f), 0.05f, vec3(0.9f, 0.8f, 0.6f)},  // near-mirror metal
};

vec3 direction_at(float cos_theta) {
  return {std::sqrt(1.0f - cos_theta * cos_theta), 0.0f, cos_theta};
}

// The directional albedo by deterministic quadrature in double precision. The Lambert lobe
// integrates to its albedo exactly. The GGX lobe is integrated over half vectors h (with
// d omega_i = 4 (wo . h) d omega_h) on a midpoint grid in (u, phi), where
// cos^2 theta_h = (1 - u) / (1 + (alpha^2 - 1) u) spreads the grid like D(h) cos(theta_h) so
// that even a narrow lobe gets resolved; the grid's measure is D(h) cos(theta_h) d omega_h.
vec3 albedo_by_quadrature(const SurfaceHit& s, vec3 wo, int n = 1024) {
  double sum[3] = {s.albedo.x, s.albedo.y, s.albedo.z};
  if (max_component(s.f0) <= 0.0f) return s.albedo;
  const double r = std::max(double(s.roughness), double(kMinRoughness));
  const double a2 = r * r * r * r;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n, phi = 2.0 * kPi * (j + 0.5) / n;
      const double cos2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u);
      const double ct = std::sqrt(cos2), st = std::sqrt(std::max(0.0, 1.0 - cos2));
      const double hx = st * std::cos(phi), hy = st * std::sin(phi), hz = ct;
      const double wo_h = wo.x * hx + wo.y * hy + wo.z * hz;
      if (wo_h <= 0.0) continue;
      const double ix = 2.0 * wo_h * hx - wo.x, iy = 2.0 * wo_h * hy - wo.y,
                   iz = 2.0 * wo_h * hz - wo.z;
      if (iz <= 0.0) continue;
      const double d = (st * st + cos2 * a2);
      const double ggx_d = a2 / (kPi * d * d);
      const vec3 wi = glm::normalize(vec3(float(ix), float(iy), float(iz)));
      const vec3 f = ggx_specular(s.normal, wo, wi, s.roughness, s.f0);
      const double weight = iz * 4.0 * wo_h / (ggx_d * ct) / (double(n) * n);
      for (int k = 0; k < 3; ++k) sum[k] += f[k] * weight;
    }
  return vec3(float(sum[0]), float(sum[1]), float(sum[2]));
}

TEST(PathSampling, ImportanceSampledAlbedoMatchesQuadrature) {
  for (const TestMaterial& m : kMaterials)
    for (float cos_o : {0.95f, 0.6f, 0.25f}) {
      const SurfaceHit s{
          .normal = vec3(0, 0, 1), .albedo = m.albedo, .f0 = m.f0, .roughness = m.roughness};
      const vec3 wo = direction_at(cos_o);
      Estimate e;
      Pcg32 rng(7);
      for (int i = 0; i < 200000; ++i) {
        const BsdfSample b = sample_bsdf(s, wo, rng.next_float(), rng.next2());
        e.add(b.valid() ? b.f * (b.wi.z / b.pdf) : vec3(0.0f));
      }
      const vec3 expected = albedo_by_quadrature(s, wo);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(e.mean(k), expected[k], 5.0 * e.standard_error(k) + 2e-3 * expected[k])
            << "roughness " << m.roughness << " cos_o " << cos_o << " channel " << k;
    }
}

TEST(PathSampling, PdfIntegratesToTheProbabilityOfAValidSample) {
  for (const TestMaterial& m : kMaterials)
    for (float cos_o : {0.9f, 0.4f}) {
      if (m.roughness < 0.1f) continue;  // too narrow a lobe for uniform integration
      const SurfaceHit s{
          .normal = vec3(0, 0, 1), .albedo = m.albedo, .f0 = m.f0, .roughness = m.roughness};
      const vec3 wo = direction_at(cos_o);
      // Integral of the pdf over the hemisphere by uniform QMC directions.
      const uint32_t n = 1 << 20;
      double integral = 0.0;
      for (uint32_t i = 0; i < n; ++i) {
        const vec2 u = sobol2(i);
        const float z = u.x, r = std::sqrt(1.0f - z * z), phi = kTwoPi * u.y;
        integral += bsdf_pdf(s, wo, vec3(r * std::cos(phi), r * std::sin(phi), z));
      }
      integral *= kTwoPi / n;
      // How often sampling gives a direction above the horizon.
      Pcg32 rng(3);
      int valid = 0;
      const int trials = 200000;
      for (int i = 0; i < trials; ++i)
        valid += sample_bsdf(s, wo, rng.next_float(), rng.next2()).pdf > 0.0f;
      EXPECT_NEAR(integral, double(valid) / trials, 0.01) << m.roughness << " " << cos_o;
      EXPECT_LE(integral, 1.005);
    }
}

TEST(PathSampling, PowerHeuristicWeightsSumToOne) {
  Pcg32 rng(11);
  for (int i = 0; i < 1000; ++i) {
    const float a = std::exp(20.0f * (rng.next_float() - 0.5f));
    const float b = std::exp(20.0f * (rng.next_float() - 0.5f));
    EXPECT_NEAR(power_heuristic(a, b) + power_heuristic(b, a), 1.0f, 1e-6f);
  }
  EXPECT_EQ(power_heuristic(1.0f, 0.0f), 1.0f);
  EXPECT_EQ(power_heuristic(0.0f, 1.0f), 0.0f);
}

TEST(PathSampling, LightPdfsMatchTheSamplers) {
  const Scene s = path_test::furnace(vec3(0.5f), vec3(1.0f));
  const vec3 p(0.2f, -0.3f, 0.1f);
  Pcg32 rng(5);
  for (int i = 0; i < 100; ++i) {
    const LightSample ls = sample_area_light(s, s.area_lights[0], p, rng.next2());
    if (!ls.valid()) continue;
    // The face the sample lies on: the cube face its point's largest coordinate marks.
    const vec3 q = p + ls.wi * ls.distance;
    vec3 n(0.0f);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(q[k]) > std::abs(q[axis])) axis = k;
    n[axis] = q[axis] > 0.0f ? -1.0f : 1.0f;
    const float pdf = area_light_pdf(s.area_lights[0], ls.distance, glm::dot(n, -ls.wi));
    EXPECT_NEAR(pdf, ls.pdf, 1e-3f * ls.pdf);
  }
  const Light sphere = Light::sphere(vec3(0, 2, 0), 0.5f, vec3(1.0f));
  const LightSample ls = sample_sphere_light(sphere, vec3(0.0f), vec2(0.3f, 0.7f));
  EXPECT_FLOAT_EQ(sphere_light_pdf(sphere, vec3(0.0f)), ls.pdf);
  EXPECT_EQ(sphere_light_pdf(sphere, vec3(0, 2.1f, 0)), 0.0f);  // inside
}

TEST(PathSampling, LightPickerFollowsPower) {
  Scene s = path_test::furnace(vec3(0.5f), vec3(1.0f));  // area 24 m^2, radiance 1
  s.lights.push_back(Light::point(vec3(0.0f), vec3(24.0f * kPi / (4.0f * kPi))));  // same power
  s.lights.push_back(Light::point(vec3(0.0f), vec3(0.0f)));                        // none
  s.finalize();
  const LightPicker picker = LightPicker::build(s);
  ASSERT_EQ(picker.pmf.size(), 3u);
  EXPECT_NEAR(picker.light_pmf(0), 0.5f, 1e-6f);
  EXPECT_EQ(picker.light_pmf(1), 0.0f);
  EXPECT_NEAR(picker.area_light_pmf(0), 0.5f, 1e-6f);
  for (float u : {0.0f, 0.25f, 0.4999f, 0.5001f, 0.75f, 0.99999994f}) {
    const uint32_t k = picker.pick(u);
    EXPECT_NE(k, 1u) << u;  // never the light without power
    EXPECT_EQ(k, u < 0.5f ? 0u : 2u) << u;
  }
  for (uint32_t t = 0; t < s.triangle_count(); ++t) EXPECT_EQ(picker.area_light_of_triangle[t], 0);
  // A light left out (one the direct pass shades apart): the others share its probability.
  const uint32_t left_out[] = {0};
  const LightPicker without = LightPicker::build(s, left_out);
  EXPECT_EQ(without.light_pmf(0), 0.0f);
  EXPECT_NEAR(without.area_light_pmf(0), 1.0f, 1e-6f);
  for (float u : {0.0f, 0.5f, 0.99999994f}) EXPECT_EQ(without.pick(u), 2u) << u;
}

// Reflected radiance at a surface point with no geometry of its own, direct light only.
// (light_candidates as PathSettings', 8 by default.)
Estimate estimate_direct(const Scene& scene, const SurfaceHit& x, vec3 wo, LightStrategy strategy,
                         int n, int light_candidates = PathSettings().light_candidates) {
  auto tracer = make_embree_tracer(scene);
  const LightPicker lights = LightPicker::build(scene);
  const SceneData data = SceneData::from(scene);
  const PathScene ps = path_scene(data.view(), *tracer, lights);
  PathSettings settings;
  settings.max_bounces = 0;
  settings.strategy = strategy;
  settings.light_candidates = light_candidates;
  PathCounters counters;
  Estimate e;
  for (int i = 0; i < n; ++i) {
    Pcg32 rng = path_rng(0, uint32_t(i), uint32_t(strategy));
    e.add(reflected_radiance(ps, settings, x, wo, rng, counters));
  }
  return e;
}

TEST(PathSampling, UniformFieldGivesRadianceTimesDirectionalAlbedo) {
  // Black walls emitting Le all round: a point in the middle reflects Le * albedo(wo).
  const vec3 le(2.0f);
  const Scene s = path_test::furnace(vec3(0.0f), le);
  for (const TestMaterial& m : kMaterials) {
    const SurfaceHit x{.position = vec3(0.1f, 0.0f, -0.2f),
                       .normal = vec3(0, 0, 1),
                       .geometric_normal = vec3(0, 0, 1),
                       .albedo = m.albedo,
                       .f0 = m.f0,
                       .roughness = m.roughness};
    const vec3 wo = direction_at(0.7f);
    const vec3 expected = le * albedo_by_quadrature(x, wo);
    for (LightStrategy strategy :
         {LightStrategy::kMis, LightStrategy::kLightOnly, LightStrategy::kBsdfOnly}) {
      // Light sampling alone cannot find a near-mirror's lobe in reasonable time.
      if (strategy == LightStrategy::kLightOnly && m.roughness < 0.1f) continue;
      const Estimate e = estimate_direct(s, x, wo, strategy, 40000);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(e.mean(k), expected[k], 5.0 * e.standard_error(k) + 2e-3 * expected[k])
            << "roughness " << m.roughness << " strategy " << int(strategy) << " channel " << k;
    }
  }
}

TEST(PathSampling, SphereLightIrradianceIsAnalytic) {
  // A sphere of radiance L and radius R at distance d above a white Lambertian point:
  // E = pi L (R / d)^2, so the reflected radiance is L (R / d)^2.
  Scene s;
  s.source = "sphere";
  const float radius = 0.3f, d = 1.0f, le = 5.0f;
  s.lights.push_back(Light::sphere(vec3(0.0f, 0.0f, d), radius, vec3(le)));
  s.finalize();
  const SurfaceHit x{.position = vec3(0.0f),
                     .normal = vec3(0, 0, 1),
                     .geometric_normal = vec3(0, 0, 1),
                     .albedo = vec3(1.0f),
                     .f0 = vec3(0.0f),
                     .roughness = 1.0f};
  const float expected = le * radius * radius / (d * d);
  for (LightStrategy strategy :
       {LightStrategy::kMis, LightStrategy::kLightOnly, LightStrategy::kBsdfOnly}) {
    const Estimate e = estimate_direct(s, x, direction_at(0.8f), strategy, 40000);
    EXPECT_NEAR(e.mean(0), expected, 5.0 * e.standard_error(0) + 1e-3 * expected) << int(strategy);
  }
}

TEST(PathSampling, PunctualLightsGiveTheirIrradiance) {
  // Point, spot and directional lights over a white Lambertian point, one picked per sample by
  // power: the reflected radiance is the summed irradiance over pi.
  Scene s;
  s.source = "punctual";
  s.lights.push_back(Light::point(vec3(0.0f, 0.0f, 2.0f), vec3(4.0f)));  // E = 4 / 2^2
  s.lights.push_back(Light::spot(vec3(1.0f, 0.0f, 1.0f), vec3(-1.0f, 0.0f, -1.0f), vec3(2.0f),
                                 20.0f, 30.0f));  // on axis: E = 2 / 2 * cos 45
  const vec3 sun = glm::normalize(vec3(0.0f, 1.0f, -1.0f));
  s.lights.push_back(Light::directional(sun, vec3(3.0f)));  // E = 3 cos 45
  s.finalize();
  const SurfaceHit x{.position = vec3(0.0f),
                     .normal = vec3(0, 0, 1),
                     .geometric_normal = vec3(0, 0, 1),
                     .albedo = vec3(1.0f),
                     .f0 = vec3(0.0f),
                     .roughness = 1.0f};
  const float c = std::sqrt(0.5f);
  const float expected = (1.0f + c + 3.0f * c) / kPi;
  const Estimate e = estimate_direct(s, x, vec3(0, 0, 1), LightStrategy::kMis, 200000);
  EXPECT_NEAR(e.mean(0), expected, 5.0 * e.standard_error(0) + 1e-4);
  EXPECT_LT(e.standard_error(0), 0.01 * expected);
}

Material floor_material(vec3 albedo, float roughness, vec3 f0) {
  Material m;
  m.albedo = albedo;
  m.roughness = roughness;
  m.f0 = f0;
  return m;
}
// A point of a floor facing up (+y) made of `m`.
SurfaceHit floor_point(vec3 position, const Material& m) {
  return {.position = position,
          .normal = vec3(0, 1, 0),
          .geometric_normal = vec3(0, 1, 0),
          .albedo = m.albedo,
          .f0 = m.f0,
          .roughness = m.roughness};
}
// Two estimates of the same radiance: their means within five combined standard errors.
void expect_same_mean(const Estimate& a, const Estimate& b, const std::string& what) {
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(a.mean(k), b.mean(k), 5.0 * std::hypot(a.standard_error(k), b.standard_error(k)))
        << what << ", channel " << k;
}

// Black, emitting `emission`.
Material lamp_material(vec3 emission) {
  Material m;
  m.albedo = vec3(0.0f);
  m.emission = emission;
  return m;
}

TEST(PathSampling, StrategiesAgreeOnAGlossyFloorUnderAQuadAndASphereLight) {
  Scene s;
  s.source = "glossy";
  const Material floor = floor_material(vec3(0.4f, 0.3f, 0.2f), 0.25f, vec3(0.6f));
  const Material lamp = lamp_material(vec3(6.0f, 5.0f, 4.0f));
  s.materials = {floor, lamp};
  Mesh mesh;
  mesh.name = "scene";
  scene_test::add_quad(mesh, vec3(-3, 0, -3), vec3(0, 0, 6), vec3(6, 0, 0), 0);
  // A 0.6 m square lamp facing down at height 1, off to the side.
  scene_test::add_quad(mesh, vec3(0.4f, 1, -0.3f), vec3(0.6f, 0, 0), vec3(0, 0, 0.6f), 1);
  s.meshes.push_back(mesh);
  s.lights.push_back(Light::sphere(vec3(-0.8f, 0.7f, 0.2f), 0.15f, vec3(20.0f)));
  s.finalize();
  ASSERT_EQ(s.area_lights.size(), 1u);
  ASSERT_GT(s.meshes[0].face_normal_area2(2).y * -1.0f, 0.0f) << "the lamp must face down";
  const SurfaceHit x = floor_point(vec3(0.0f), floor);
  for (vec3 wo : {glm::normalize(vec3(-1.0f, 0.8f, 0.0f)), glm::normalize(vec3(1.0f, 1.2f, 0.0f)),
                  vec3(0, 1, 0)}) {
    const Estimate mis = estimate_direct(s, x, wo, LightStrategy::kMis, 100000);
    const Estimate light = estimate_direct(s, x, wo, LightStrategy::kLightOnly, 100000);
    const Estimate bsdf = estimate_direct(s, x, wo, LightStrategy::kBsdfOnly, 100000);
    expect_same_mean(mis, light, "light sampling alone");
    expect_same_mean(mis, bsdf, "BSDF sampling alone");
    for (int k = 0; k < 3; ++k) {
      // MIS is never much worse than the better of the two.
      EXPECT_LT(mis.standard_error(k),
                1.5 * std::min(light.standard_error(k), bsdf.standard_error(k)));
      EXPECT_LT(mis.standard_error(k), 0.02 * mis.mean(k)) << "too noisy to test anything";
    }
  }
}

// A glossy floor under 30 lamps of equal power (24 small quads facing down, 4 sphere lights and
// 2 quads facing up, under the floor's reach), all but a few far off: next-event estimation
// that picks a lamp by power mostly picks a far one. Resampled from candidates it must give
// the same mean with less noise, and the light strategies must still agree: the MIS weights of
// the resampled samples are the power pick's on both sides.
TEST(PathSampling, ResampledLightSamplesAgreeWithPowerPicksAndAreLessNoisy) {
  Scene s;
  s.source = "many lamps";
  const Material floor = floor_material(vec3(0.5f, 0.4f, 0.3f), 0.4f, vec3(0.3f));
  const Material lamp = lamp_material(vec3(8.0f, 7.0f, 5.0f));
  s.materials = {floor};
  Mesh mesh;
  mesh.name = "scene";
  scene_test::add_quad(mesh, vec3(-10, 0, -10), vec3(0, 0, 20), vec3(20, 0, 0), 0);
  // Each lamp of its own material: one area light each.
  const auto add_lamp = [&](vec3 corner, vec3 u, vec3 v) {
    s.materials.push_back(lamp);
    scene_test::add_quad(mesh, corner, u, v, uint32_t(s.materials.size() - 1));
  };
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j)  // facing down
      add_lamp(vec3(-7.5f + 3.0f * float(i), 1.0f + 0.2f * float(j), -6.0f + 4.0f * float(j)),
               vec3(0.3f, 0, 0), vec3(0, 0, 0.3f));
  for (int i = 0; i < 2; ++i)  // facing up, above the floor: no light reaches x
    add_lamp(vec3(-3.0f + 5.0f * float(i), 0.5f, 2.0f), vec3(0, 0, 0.3f), vec3(0.3f, 0, 0));
  s.meshes.push_back(mesh);
  for (int i = 0; i < 4; ++i)
    s.lights.push_back(
        Light::sphere(vec3(-6.0f + 4.0f * float(i), 1.5f, 7.0f), 0.1f, vec3(6.0f, 5.0f, 4.0f)));
  s.finalize();
  ASSERT_EQ(s.area_lights.size(), 26u);
  const SurfaceHit x = floor_point(vec3(0.2f, 0.0f, 0.1f), floor);
  const vec3 wo = glm::normalize(vec3(-1.0f, 1.0f, 0.3f));
  const Estimate picked = estimate_direct(s, x, wo, LightStrategy::kMis, 100000, 1);
  const Estimate resampled = estimate_direct(s, x, wo, LightStrategy::kMis, 100000);
  const Estimate light = estimate_direct(s, x, wo, LightStrategy::kLightOnly, 100000);
  const Estimate bsdf = estimate_direct(s, x, wo, LightStrategy::kBsdfOnly, 100000);
  expect_same_mean(resampled, picked, "picked by power");
  expect_same_mean(resampled, light, "light sampling alone");
  expect_same_mean(resampled, bsdf, "BSDF sampling alone");
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(resampled.standard_error(k), 0.5 * picked.standard_error(k)) << "channel " << k;
    EXPECT_LT(resampled.standard_error(k), 0.02 * resampled.mean(k)) << "too noisy to test";
  }
}

// A point in a narrow spot's beam, among three lamps of far more power (the flashlight in a
// level lit by its lamps): picked by power, the spot is the light sampled in one estimate of
// about thirty, and the point's light is mostly its. With few lights each next-event estimate
// resamples a sample of every light instead: the same mean, a fraction of the noise.
TEST(PathSampling, FewLightsResampledFromASampleOfEachAgreeWithPowerPicksAndAreLessNoisy) {
  Scene s;
  s.source = "a beam among lamps";
  const Material floor = floor_material(vec3(0.5f, 0.45f, 0.4f), 0.6f, vec3(0.04f));
  s.materials = {floor};
  Mesh mesh;
  mesh.name = "scene";
  scene_test::add_quad(mesh, vec3(-10, 0, -10), vec3(0, 0, 20), vec3(20, 0, 0), 0);
  for (int i = 0; i < 3; ++i) {  // 1 m^2 lamps facing down, 4 to 8 m away
    s.materials.push_back(lamp_material(vec3(10.0f)));
    scene_test::add_quad(mesh, vec3(-8.0f + 6.0f * float(i), 3.0f, -6.0f), vec3(1, 0, 0),
                         vec3(0, 0, 1), uint32_t(s.materials.size() - 1));
  }
  s.meshes.push_back(mesh);
  s.lights.push_back(Light::spot(vec3(0.0f, 2.0f, 0.0f), vec3(0, -1, 0), vec3(40.0f), 5.0f, 8.0f));
  s.finalize();
  const LightPicker picker = LightPicker::build(s);
  ASSERT_EQ(picker.pmf.size(), 4u);
  ASSERT_LT(picker.light_pmf(0), 0.05f);  // the spot: rarely picked by power
  const SurfaceHit x = floor_point(vec3(0.1f, 0.0f, -0.05f), floor);
  const vec3 wo = glm::normalize(vec3(0.3f, 1.0f, 0.2f));
  const Estimate picked = estimate_direct(s, x, wo, LightStrategy::kMis, 100000, 1);
  const Estimate resampled = estimate_direct(s, x, wo, LightStrategy::kMis, 100000);
  const Estimate light = estimate_direct(s, x, wo, LightStrategy::kLightOnly, 100000);
  expect_same_mean(resampled, picked, "picked by power");
  expect_same_mean(resampled, light, "light sampling alone");
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(resampled.standard_error(k), 0.25 * picked.standard_error(k)) << "channel " << k;
    EXPECT_LT(resampled.standard_error(k), 0.01 * resampled.mean(k)) << "too noisy to test";
  }
}

}  // namespace
}  // namespace bounce
