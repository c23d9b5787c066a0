#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/scene/load.h"
#include "bounce/trace/trace_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {
namespace {

// The Cornell box with three sphere lights inside (one of them behind the box's short block's
// line of sight from many rays), and a copy without them for the triangle-only answer.
Scene cornell_with_spheres() {
  Scene s = make_cornell();
  s.lights.push_back(Light::sphere(vec3(0.15f, 0.2f, 0.25f), 0.06f, vec3(5.0f)));
  s.lights.push_back(Light::point(vec3(0.3f, 0.5f, 0.3f), vec3(1.0f)));
  s.lights.push_back(Light::sphere(vec3(0.4f, 0.35f, 0.3f), 0.1f, vec3(2.0f, 3.0f, 4.0f)));
  s.lights.push_back(Light::sphere(vec3(0.28f, 0.45f, 0.1f), 0.04f, vec3(1.0f)));
  s.finalize();
  return s;
}

// Ray against sphere in double precision: the analytic reference.
double sphere_distance(const Ray& r, vec3 centre, float radius) {
  const glm::dvec3 oc = glm::dvec3(centre) - glm::dvec3(r.origin), d(r.direction);
  const double b = glm::dot(oc, d);
  const double disc = b * b - (glm::dot(oc, oc) - double(radius) * radius);
  if (disc < 0.0) return INFINITY;
  const double root = std::sqrt(disc);
  const double t = b - root > r.tmin ? b - root : b + root;
  return t > r.tmin ? t : INFINITY;
}

std::vector<Ray> random_rays(int n, uint32_t seed) {
  Pcg32 rng(seed);
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    Ray r;
    // From inside the box, towards anywhere; some rays end early.
    r.origin =
        vec3(0.05f, 0.05f, 0.05f) +
        vec3(0.45f, 0.45f, 0.45f) * vec3(rng.next_float(), rng.next_float(), rng.next_float());
    r.direction = sample_uniform_sphere(rng.next2());
    if (i % 4 == 0) r.tmax = 0.3f * rng.next_float();
    rays.push_back(r);
  }
  return rays;
}

TEST(TraceView, ClosestHitIsTheNearerOfTrianglesAndSphereLights) {
  const Scene scene = cornell_with_spheres();
  const Scene triangles_only = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const auto reference = make_embree_tracer(triangles_only);
  const TraceView view = tracer->view();
  ASSERT_EQ(view.sphere_count, 3u);
  int sphere_hits = 0, triangle_hits = 0;
  for (const Ray& ray : random_rays(4000, 5)) {
    const Hit triangle = reference->intersect(ray);
    double nearest = triangle.valid() ? triangle.t : INFINITY;
    uint32_t light = Hit::kNone;
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
      const Light& l = scene.lights[i];
      if (l.type != LightType::kSphere) continue;
      const double t = sphere_distance(ray, l.position, l.radius);
      if (t < nearest && t < ray.tmax) {
        nearest = t;
        light = i;
      }
    }
    const Hit hit = view.intersect(ray);
    ASSERT_EQ(hit.light, light);
    if (light != Hit::kNone) {
      ++sphere_hits;
      EXPECT_FALSE(hit.valid());
      EXPECT_NEAR(hit.t, nearest, 1e-5 * nearest);
    } else {
      EXPECT_EQ(hit.mesh, triangle.mesh);
      EXPECT_EQ(hit.triangle, triangle.triangle);
      EXPECT_EQ(hit.t, triangle.t);
      triangle_hits += hit.valid();
    }
    // Occlusion agrees with the closest hit.
    EXPECT_EQ(view.occluded(ray), hit.any()) << ray.tmax;
  }
  EXPECT_GT(sphere_hits, 100);
  EXPECT_GT(triangle_hits, 1000);
}

TEST(TraceView, TracerCallsAnswerAsTheViewDoes) {
  const Scene scene = cornell_with_spheres();
  const auto tracer = make_embree_tracer(scene);
  const TraceView view = tracer->view();
  const std::vector<Ray> rays = random_rays(3000, 8);
  std::vector<Hit> stream(rays.size()), coherent(rays.size());
  std::vector<uint8_t> blocked(rays.size());
  tracer->intersect(rays, stream, false);
  tracer->intersect(rays, coherent, true);
  tracer->occluded(rays, blocked);
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit single = tracer->intersect(rays[i]);
    const Hit expected = view.intersect(rays[i]);
    for (const Hit& h : {single, stream[i], coherent[i]}) {
      EXPECT_EQ(h.light, expected.light) << i;
      EXPECT_EQ(h.mesh, expected.mesh) << i;
      EXPECT_EQ(h.triangle, expected.triangle) << i;
      if (expected.any()) {
        EXPECT_NEAR(h.t, expected.t, 1e-6f * (1.0f + expected.t)) << i;
      }
    }
    EXPECT_EQ(bool(blocked[i]), view.occluded(rays[i])) << i;
    EXPECT_EQ(tracer->occluded(rays[i]), view.occluded(rays[i])) << i;
  }
}

TEST(TraceView, FollowsASphereLightThatMoved) {
  Scene scene = cornell_with_spheres();
  const auto tracer = make_embree_tracer(scene);
  // A ray through where the first sphere light is, and then where it moves to.
  const Ray before{vec3(0.15f, 0.2f, 0.05f), 0.0f, vec3(0.0f, 0.0f, 1.0f)};
  const Ray after{vec3(0.15f, 0.3f, 0.05f), 0.0f, vec3(0.0f, 0.0f, 1.0f)};
  EXPECT_EQ(tracer->view().intersect(before).light, 0u);
  EXPECT_NE(tracer->view().intersect(after).light, 0u);
  scene.lights[0].position.y = 0.3f;
  scene.derive();
  tracer->update(scene, {});
  EXPECT_NE(tracer->view().intersect(before).light, 0u);
  EXPECT_EQ(tracer->view().intersect(after).light, 0u);
  EXPECT_NEAR(tracer->view().intersect(after).t, 0.2f - 0.06f, 1e-5f);
}

}  // namespace
}  // namespace bounce
