// Energy balance in the Cornell box: the power the lights emit equals the power the surfaces
// absorb plus the power that escapes through the open front. Each side is measured with the path
// tracer's own estimator, so a bias anywhere in it (MIS, roulette, light picking) shows up.
#include <gtest/gtest.h>

#include <algorithm>

#include "bounce/core/sampling.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/techniques/path/path_tracer.h"
#include "path_test_util.h"

namespace bounce {
namespace {

using path_test::Estimate;

TEST(PathEnergy, CornellAbsorbedPlusEscapedEqualsEmitted) {
  const Scene s = make_cornell();
  // With Lambert surfaces only, a surface absorbs (1 - albedo) of its irradiance.
  for (const Material& m : s.materials) ASSERT_EQ(max_component(m.f0), 0.0f) << m.name;
  auto tracer = make_embree_tracer(s);
  const LightPicker lights = LightPicker::build(s);
  const SceneData data = SceneData::from(s);
  const PathScene ps = path_scene(data.view(), *tracer, lights);
  PathSettings settings;  // all bounces, roulette from vertex 3
  PathCounters counters;

  vec3 emitted(0.0f);
  for (const AreaLight& l : s.area_lights) emitted += l.power();

  // Absorbed: a point uniform over all triangle area, either side. A white Lambertian probe
  // there reflects E / pi, which gives the irradiance E.
  std::vector<float> cdf;
  std::vector<TriangleRef> refs;
  float area = 0.0f;
  for (uint32_t m = 0; m < s.meshes.size(); ++m)
    for (uint32_t t = 0; t < s.meshes[m].triangle_count(); ++t) {
      area += 0.5f * glm::length(s.meshes[m].face_normal_area2(t));
      cdf.push_back(area);
      refs.push_back({m, t});
    }
  Estimate absorbed;
  for (int i = 0; i < 250000; ++i) {
    Pcg32 rng = path_rng(1, uint32_t(i), 0);
    const float u = rng.next_float() * area;
    const size_t k = std::min(size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()),
                              refs.size() - 1);
    const Mesh& mesh = s.meshes[refs[k].mesh];
    const uvec3 tri = mesh.triangles[refs[k].triangle];
    const vec2 b = sample_uniform_triangle(rng.next2());
    const vec3 q = (1.0f - b.x - b.y) * mesh.positions[tri.x] + b.x * mesh.positions[tri.y] +
                   b.y * mesh.positions[tri.z];
    vec3 normal = glm::normalize(mesh.face_normal_area2(refs[k].triangle));
    if (rng.next_float() < 0.5f) normal = -normal;
    const vec3 albedo = s.albedo(s.materials[mesh.materials[refs[k].triangle]], vec2(0.0f));
    // The light hangs 0.1 mm below the ceiling, closer than a ray's start offset: the faces
    // that look into that gap (the ceiling above the light, the light's back) get no light
    // through it that matters here, so they count as dark.
    const vec3 start = offset_origin(q, normal);
    if (tracer->occluded(Ray{q, 1e-7f, normal, glm::length(start - q)})) {
      absorbed.add(vec3(0.0f));
      continue;
    }
    const SurfaceHit probe{.position = q,
                           .normal = normal,
                           .geometric_normal = normal,
                           .albedo = vec3(1.0f),
                           .f0 = vec3(0.0f),
                           .roughness = 1.0f};
    const vec3 irradiance = kPi * reflected_radiance(ps, settings, probe, normal, rng, counters);
    absorbed.add((vec3(1.0f) - albedo) * irradiance * (2.0f * area));
  }

  // Escaped: the box is closed but for its front, the quad at z = 0 between the walls' front
  // edges. The flux out through it is the irradiance on its inner side (a probe facing +z).
  const vec3 opening[4] = {vec3(0.0f, 0.0f, 0.0f), vec3(0.5528f, 0.0f, 0.0f),
                           vec3(0.5560f, 0.5488f, 0.0f), vec3(0.0f, 0.5488f, 0.0f)};
  const float area0 =
      0.5f * glm::length(glm::cross(opening[1] - opening[0], opening[2] - opening[0]));
  const float area1 =
      0.5f * glm::length(glm::cross(opening[2] - opening[0], opening[3] - opening[0]));
  const vec3 inward(0.0f, 0.0f, 1.0f);
  Estimate escaped;
  for (int i = 0; i < 50000; ++i) {
    Pcg32 rng = path_rng(2, uint32_t(i), 0);
    const bool first = rng.next_float() * (area0 + area1) < area0;
    const vec3 a = opening[0], b = opening[first ? 1 : 2], c = opening[first ? 2 : 3];
    const vec2 w = sample_uniform_triangle(rng.next2());
    const vec3 q = (1.0f - w.x - w.y) * a + w.x * b + w.y * c;
    const SurfaceHit probe{.position = q,
                           .normal = inward,
                           .geometric_normal = inward,
                           .albedo = vec3(1.0f),
                           .f0 = vec3(0.0f),
                           .roughness = 1.0f};
    escaped.add(reflected_radiance(ps, settings, probe, inward, rng, counters) *
                (kPi * (area0 + area1)));
  }

  EXPECT_EQ(counters.nonfinite, 0u);
  for (int k = 0; k < 3; ++k) {
    const double total = absorbed.mean(k) + escaped.mean(k);
    const double se = std::hypot(absorbed.standard_error(k), escaped.standard_error(k));
    EXPECT_LT(se, 0.01 * emitted[k]) << "channel " << k << ": too noisy to test anything";
    EXPECT_NEAR(total, emitted[k], 4.0 * se)
        << "channel " << k << ": absorbed " << absorbed.mean(k) << " escaped " << escaped.mean(k);
  }
}

}  // namespace
}  // namespace bounce
