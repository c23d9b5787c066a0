#include <gtest/gtest.h>

#include <optional>

#include "bounce/core/error.h"
#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/core/timer.h"
#include "bounce/trace/tracer.h"

namespace bounce {
namespace {

// Moller-Trumbore ray/triangle intersection in double precision: the analytic reference.
std::optional<Hit> intersect_triangle(const Ray& r, vec3 p0, vec3 p1, vec3 p2) {
  const glm::dvec3 o(r.origin), d(r.direction), a(p0), e1 = glm::dvec3(p1) - a,
                                                       e2 = glm::dvec3(p2) - a;
  const glm::dvec3 pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  if (std::abs(det) < 1e-12) return std::nullopt;
  const glm::dvec3 tv = o - a;
  const double u = glm::dot(tv, pv) / det;
  const glm::dvec3 qv = glm::cross(tv, e1);
  const double v = glm::dot(d, qv) / det;
  const double t = glm::dot(e2, qv) / det;
  if (u < 0 || v < 0 || u + v > 1 || t < r.tmin || t > r.tmax) return std::nullopt;
  Hit h;
  h.t = float(t);
  h.barycentric = vec2(float(u), float(v));
  return h;
}

Scene random_triangles(int meshes, int per_mesh, uint32_t seed) {
  Scene s;
  s.source = "random triangles";
  s.materials.push_back(Material{});
  Pcg32 rng(seed);
  for (int m = 0; m < meshes; ++m) {
    Mesh mesh;
    mesh.name = fmt::format("mesh{}", m);
    for (int t = 0; t < per_mesh; ++t) {
      const vec3 c = 4.0f * vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 2.0f;
      for (int k = 0; k < 3; ++k)
        mesh.positions.push_back(
            c + 0.6f * (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f));
      mesh.triangles.push_back(uvec3(3 * t, 3 * t + 1, 3 * t + 2));
      mesh.materials.push_back(0);
    }
    s.meshes.push_back(std::move(mesh));
  }
  s.finalize();
  return s;
}

TEST(EmbreeTracer, ClosestHitsMatchBruteForceAnalyticIntersection) {
  const Scene scene = random_triangles(3, 60, 7);
  const auto tracer = make_embree_tracer(scene);
  Pcg32 rng(11);
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    Ray r;
    r.origin = 5.0f * sample_uniform_sphere(rng.next2());
    const vec3 target = 3.0f * (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f);
    r.direction = glm::normalize(target - r.origin);
    r.tmax = i % 5 == 0 ? 4.0f : r.tmax;  // some rays end early
    rays.push_back(r);
  }
  std::vector<Hit> packet_hits(rays.size());
  tracer->intersect(rays, packet_hits, true);
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    std::optional<Hit> best;
    for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
      const Mesh& mesh = scene.meshes[m];
      for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        const uvec3 tri = mesh.triangles[t];
        auto h = intersect_triangle(rays[i], mesh.positions[tri.x], mesh.positions[tri.y],
                                    mesh.positions[tri.z]);
        if (h && (!best || h->t < best->t)) {
          best = h;
          best->mesh = m;
          best->triangle = t;
        }
      }
    }
    const Hit single = tracer->intersect(rays[i]);
    for (const Hit& got : {single, packet_hits[i]}) {
      ASSERT_EQ(got.valid(), best.has_value()) << "ray " << i;
      if (!best) continue;
      EXPECT_EQ(got.mesh, best->mesh) << "ray " << i;
      EXPECT_EQ(got.triangle, best->triangle) << "ray " << i;
      EXPECT_NEAR(got.t, best->t, 1e-4f * best->t);
      EXPECT_NEAR(got.barycentric.x, best->barycentric.x, 1e-4f);
      EXPECT_NEAR(got.barycentric.y, best->barycentric.y, 1e-4f);
    }
    hits += best.has_value();
    // Occlusion agrees with the closest hit over the same interval.
    std::vector<uint8_t> blocked(1);
    tracer->occluded(std::span<const Ray>(&rays[i], 1), blocked);
    EXPECT_EQ(bool(blocked[0]), best.has_value());
    EXPECT_EQ(tracer->occluded(rays[i]), best.has_value());
  }
  EXPECT_GT(hits, 200);   // the test exercises hits...
  EXPECT_LT(hits, 1900);  // ...and misses
}

TEST(EmbreeTracer, ReportsMemoryAndBuildTime) {
  const Scene scene = random_triangles(1, 1000, 3);
  // The build time is part of the time the construction takes, in milliseconds: a clock
  // around the call bounds it (no bound on the time itself).
  Stopwatch construction;
  const auto tracer = make_embree_tracer(scene);
  const double construction_ms = construction.elapsed_ms();
  EXPECT_GT(tracer->stats().memory_bytes, 1000u * 36u);
  EXPECT_GT(tracer->stats().build_ms, 0.0);
  EXPECT_LE(tracer->stats().build_ms, construction_ms);
  // A rebuild measures itself again, within its own call.
  Stopwatch rebuild;
  tracer->rebuild(scene);
  const double rebuild_ms = rebuild.elapsed_ms();
  EXPECT_GT(tracer->stats().build_ms, 0.0);
  EXPECT_LE(tracer->stats().build_ms, rebuild_ms);
}

}  // namespace
}  // namespace bounce
