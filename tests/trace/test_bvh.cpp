// Our own BVH (trace/bvh.h) against Embree: the same closest triangle, distance and weights, and
// the same occlusion answers, on random and camera rays over the built-in scenes and a glTF model;
// refit against a fresh Embree build of the moved scene; the trace view's host path; edge cases.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <tuple>
#include <vector>

#include "bounce/core/rng.h"
#include "bounce/core/sampling.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/load.h"
#include "bounce/trace/bvh.h"
#include "bounce/trace/bvh_tracer.h"
#include "bounce/trace/bvh_traversal.h"
#include "bounce/trace/tracer.h"
#include "scene/gltf_export.h"

namespace bounce {
namespace {

// Random rays: origins inside the scene's bounds widened by a fifth, directions uniform; one in
// four ends at a random distance short of the bounds' diagonal.
std::vector<Ray> random_rays(const Scene& scene, int n, uint32_t seed) {
  const vec3 lo = scene.bounds.lo, extent = scene.bounds.hi - scene.bounds.lo;
  const float diagonal = glm::length(extent);
  Pcg32 rng(seed);
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    Ray r;
    const vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
    r.origin = lo - 0.1f * extent + 1.2f * extent * u;
    r.direction = sample_uniform_sphere(rng.next2());
    if (i % 4 == 0) r.tmax = diagonal * rng.next_float();
    rays.push_back(r);
  }
  return rays;
}

// One ray through each pixel centre of a small image from the scene's camera.
std::vector<Ray> camera_rays(const Scene& scene, int width, int height) {
  const CameraRays cam = CameraRays::from(scene.camera, width, height);
  std::vector<Ray> rays;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      rays.push_back({cam.origin, 0.0f, cam.direction(x + 0.5f, y + 0.5f)});
  return rays;
}

bool close(float a, float b, float relative, float absolute) {
  return std::abs(a - b) <= std::max(relative * std::max(std::abs(a), std::abs(b)), absolute);
}

// Positions are floats, so where a ray meets a triangle is known to a few ulps of the scene's
// coordinates, whatever the test: distances agree within 1e-5 relative, or within four ulps of
// the largest coordinate for hits so near the origin that the relative bound is finer than that.
float distance_floor(const Scene& scene) {
  const vec3 m = glm::max(glm::abs(scene.bounds.lo), glm::abs(scene.bounds.hi));
  return 4.0f * std::numeric_limits<float>::epsilon() * std::max(m.x, std::max(m.y, m.z));
}

// Compares the BVH tracer with Embree ray by ray. A ray through an edge or a corner shared by
// triangles may pick either of them (both tracers are right): such a difference is accepted only
// when the two distances agree (as above), and counted. Returns the number of hits.
int expect_same_as_embree(const Scene& scene, const Tracer& embree, const Tracer& bvh,
                          const std::vector<Ray>& rays, const char* what) {
  const float floor = distance_floor(scene);
  std::vector<Hit> stream(rays.size());
  bvh.intersect(rays, stream, true);
  std::vector<uint8_t> blocked(rays.size());
  bvh.occluded(rays, blocked);
  int hits = 0, ties = 0, failures = 0;
  for (size_t i = 0; i < rays.size() && failures < 10; ++i) {
    const Hit want = embree.intersect(rays[i]);
    const Hit got = bvh.intersect(rays[i]);
    EXPECT_EQ(stream[i].mesh, got.mesh);
    EXPECT_EQ(stream[i].triangle, got.triangle);
    EXPECT_EQ(stream[i].t, got.t);
    if (got.valid() != want.valid()) {
      ADD_FAILURE() << what << " ray " << i << ": bvh " << (got.valid() ? "hits" : "misses")
                    << " (t " << got.t << "), embree " << (want.valid() ? "hits" : "misses")
                    << " (t " << want.t << ")";
      ++failures;
      continue;
    }
    if (want.valid()) {
      ++hits;
      if (got.mesh != want.mesh || got.triangle != want.triangle) {
        if (close(got.t, want.t, 1e-5f, floor)) {
          ++ties;
        } else {
          ADD_FAILURE() << what << " ray " << i << ": bvh hits " << got.mesh << "/" << got.triangle
                        << " at " << got.t << ", embree " << want.mesh << "/" << want.triangle
                        << " at " << want.t;
          ++failures;
        }
      } else {
        EXPECT_TRUE(close(got.t, want.t, 1e-5f, floor))
            << what << " ray " << i << ": t " << got.t << " vs " << want.t;
        EXPECT_NEAR(got.barycentric.x, want.barycentric.x, 1e-3f) << what << " ray " << i;
        EXPECT_NEAR(got.barycentric.y, want.barycentric.y, 1e-3f) << what << " ray " << i;
      }
    }
    const bool want_blocked = embree.occluded(rays[i]);
    EXPECT_EQ(bvh.occluded(rays[i]), want_blocked) << what << " ray " << i;
    EXPECT_EQ(bool(blocked[i]), want_blocked) << what << " ray " << i;
    // The same ray cut short just before Embree's hit is not blocked by anything.
    if (want.valid() && want.t > 1e-3f) {
      Ray shorter = rays[i];
      shorter.tmax = want.t * (1.0f - 1e-4f);
      EXPECT_EQ(bvh.occluded(shorter), embree.occluded(shorter)) << what << " ray " << i;
    }
  }
  EXPECT_EQ(failures, 0) << what;
  // Shared-edge ties are rare: more would mean the traversal picks wrong triangles.
  EXPECT_LE(ties, int(rays.size() / 1000) + 2) << what;
  std::printf("%s: %zu rays, %d hits, %d shared-edge ties\n", what, rays.size(), hits, ties);
  return hits;
}

void expect_same_as_embree(const Scene& scene, const char* name) {
  const auto embree = make_embree_tracer(scene);
  const auto bvh = make_bvh_tracer(scene);
  const std::vector<Ray> incoherent = random_rays(scene, 20000, 5);
  const int random_hits = expect_same_as_embree(scene, *embree, *bvh, incoherent,
                                                (std::string(name) + " random").c_str());
  EXPECT_GT(random_hits, 1000);
  const std::vector<Ray> coherent = camera_rays(scene, 96, 64);
  const int camera_hits = expect_same_as_embree(scene, *embree, *bvh, coherent,
                                                (std::string(name) + " camera").c_str());
  EXPECT_GT(camera_hits, 1000);
}

TEST(Bvh, MatchesEmbreeOnCornell) {
  expect_same_as_embree(make_cornell(), "cornell");
}

TEST(Bvh, MatchesEmbreeOnCubes10000) {
  expect_same_as_embree(make_cubes(10000), "cubes:10000");
}

TEST(Bvh, MatchesEmbreeOnALoadedGltfModel) {
  // No glTF file is checked in: write a scene of turned cubes in a room as .glb and load it.
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "bounce-bvh-cubes.glb";
  write_scene_as_gltf(make_cubes(800, 9), path.string(), true);
  const Scene scene = load_scene(path.string());
  ASSERT_GT(scene.triangle_count(), 9000u);
  expect_same_as_embree(scene, "glb");
}

// Every triangle once in the leaves, leaves no larger than allowed, every box holding what is
// below it, and a depth the traversal's stack covers.
TEST(Bvh, TreeHoldsEveryTriangleOnceInsideItsBoxes) {
  const Scene scene = make_cubes(3000, 4);
  const Bvh bvh(scene);
  ASSERT_EQ(bvh.triangles().size(), scene.triangle_count());
  ASSERT_LE(bvh.depth(), uint32_t(bvh_detail::kStackSize));
  std::vector<int> seen(scene.triangle_count(), 0);
  std::vector<uint32_t> offsets;
  uint32_t offset = 0;
  for (const Mesh& m : scene.meshes) {
    offsets.push_back(offset);
    offset += uint32_t(m.triangles.size());
  }
  const auto inside = [](const float* box, vec4 p) {
    for (int a = 0; a < 3; ++a)
      if (p[a] < box[a] || p[a] > box[a + 3]) return false;
    return true;
  };
  // Walk from the root; each inner child's own two boxes lie inside the box its parent holds.
  std::vector<std::pair<uint32_t, const float*>> stack{{0u, nullptr}};
  size_t visited = 0;
  while (!stack.empty()) {
    const auto [index, parent_box] = stack.back();
    stack.pop_back();
    ++visited;
    const BvhNode& node = bvh.nodes()[index];
    for (int k = 0; k < 2; ++k) {
      if (parent_box)
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(node.box[k][a], parent_box[a]);
          EXPECT_LE(node.box[k][a + 3], parent_box[a + 3]);
        }
      if (node.child[k] & BvhNode::kLeaf) {
        EXPECT_LE(node.count[k], Bvh::kMaxLeafSize);
        const uint32_t first = node.child[k] & ~BvhNode::kLeaf;
        for (uint32_t t = first; t < first + node.count[k]; ++t) {
          const BvhTriangleId id = bvh.ids()[t];
          ++seen[offsets[id.mesh] + id.triangle];
          const BvhTriangle& tri = bvh.triangles()[t];
          EXPECT_TRUE(inside(node.box[k], tri.v0) && inside(node.box[k], tri.v1) &&
                      inside(node.box[k], tri.v2));
          const uvec3 v = scene.meshes[id.mesh].triangles[id.triangle];
          EXPECT_EQ(vec3(tri.v1), scene.meshes[id.mesh].positions[v.y]);
        }
      } else {
        ASSERT_LT(node.child[k], bvh.nodes().size());
        EXPECT_GT(node.child[k], index);  // parents before children (refit relies on it)
        stack.push_back({node.child[k], node.box[k]});
      }
    }
  }
  EXPECT_EQ(visited, bvh.nodes().size());
  for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "triangle " << i;
}

TEST(Bvh, BuildIsTheSameWhateverTheThreadCount) {
  const Scene scene = make_cubes(2000, 6);
  const Bvh parallel(scene);
  Bvh serial;
  tbb::task_arena one_thread(1);
  one_thread.execute([&] { serial.build(scene); });
  ASSERT_EQ(parallel.nodes().size(), serial.nodes().size());
  EXPECT_EQ(std::memcmp(parallel.nodes().data(), serial.nodes().data(),
                        parallel.nodes().size() * sizeof(BvhNode)),
            0);
  EXPECT_EQ(std::memcmp(parallel.ids().data(), serial.ids().data(),
                        parallel.ids().size() * sizeof(BvhTriangleId)),
            0);
}

TEST(Bvh, RefitAfterMovingMeshesMatchesAFreshEmbreeBuild) {
  Scene scene = make_cubes(2000, 2);
  ASSERT_GE(scene.meshes.size(), 3u);
  BvhTracer tracer(scene);
  const size_t nodes = tracer.bvh().nodes().size();
  // Move and turn the cubes, and lift the room's light: two meshes move, the rest stays.
  uint32_t cubes = 0, light = 0;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m].name == "cubes") cubes = m;
    if (scene.meshes[m].name == "light") light = m;
  }
  ASSERT_NE(cubes, light);
  const mat4 turn = glm::rotate(glm::translate(mat4(1.0f), vec3(0.3f, 0.2f, -0.4f)), 0.3f,
                                vec3(0.0f, 1.0f, 0.0f));
  scene.meshes[cubes].transform(turn);
  scene.meshes[light].transform(glm::translate(mat4(1.0f), vec3(0.0f, -0.5f, 0.0f)));
  scene.derive();
  const uint32_t moved[] = {cubes, light};
  tracer.update(scene, moved);
  EXPECT_EQ(tracer.bvh().nodes().size(), nodes);  // refitted, not rebuilt
  const auto embree = make_embree_tracer(scene);
  expect_same_as_embree(scene, *embree, tracer, random_rays(scene, 20000, 8), "refit random");
  expect_same_as_embree(scene, *embree, tracer, camera_rays(scene, 64, 48), "refit camera");

  // A mesh that gains a triangle cannot be refitted: the tree is rebuilt and still right.
  Mesh& m = scene.meshes[light];
  m.positions.push_back(vec3(0.0f, 3.0f, 0.0f));
  m.positions.push_back(vec3(1.0f, 3.0f, 0.0f));
  m.positions.push_back(vec3(0.0f, 3.0f, 1.0f));
  const uint32_t base = uint32_t(m.positions.size()) - 3;
  m.triangles.push_back(uvec3(base, base + 1, base + 2));
  m.materials.push_back(m.materials.back());
  scene.derive();
  Bvh bvh = tracer.bvh();
  EXPECT_FALSE(bvh.refit(scene, std::span<const uint32_t>(&light, 1)));
  tracer.update(scene, std::span<const uint32_t>(&light, 1));
  EXPECT_EQ(tracer.bvh().triangles().size(), scene.triangle_count());
  const auto embree_after = make_embree_tracer(scene);
  expect_same_as_embree(scene, *embree_after, tracer, random_rays(scene, 5000, 9),
                        "rebuilt random");
}

// The trace view with the BVH set (and no Embree scene) answers as BvhTracer does, sphere lights
// included, and as Embree's view does.
TEST(Bvh, TraceViewOnTheHostTracesTheBvh) {
  Scene scene = make_cornell();
  scene.lights.push_back(Light::sphere(vec3(0.15f, 0.2f, 0.25f), 0.06f, vec3(5.0f)));
  scene.lights.push_back(Light::sphere(vec3(0.4f, 0.35f, 0.3f), 0.1f, vec3(2.0f)));
  scene.finalize();
  const auto tracer = make_bvh_tracer(scene);
  const auto embree = make_embree_tracer(scene);
  const Bvh bvh(scene);
  const std::vector<TraceSphere> spheres = trace_spheres(scene);
  TraceView view;
  view.spheres = spheres.data();
  view.sphere_count = uint32_t(spheres.size());
  view.bvh = bvh.view();
  ASSERT_EQ(tracer->view().triangles, nullptr);
  const std::vector<Ray> rays = random_rays(scene, 5000, 3);
  std::vector<Hit> hits(rays.size());
  tracer->intersect(rays, hits);
  std::vector<uint8_t> blocked(rays.size());
  tracer->occluded(rays, blocked);
  int lights = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit got = view.intersect(rays[i]);
    EXPECT_EQ(got.t, hits[i].t) << i;
    EXPECT_EQ(got.mesh, hits[i].mesh) << i;
    EXPECT_EQ(got.triangle, hits[i].triangle) << i;
    EXPECT_EQ(got.light, hits[i].light) << i;
    EXPECT_EQ(view.occluded(rays[i]), bool(blocked[i])) << i;
    const Hit want = embree->view().intersect(rays[i]);
    EXPECT_EQ(got.light, want.light) << i;
    if (!got.sphere_light()) {
      EXPECT_EQ(got.valid(), want.valid()) << i;
    }
    lights += got.sphere_light();
  }
  EXPECT_GT(lights, 50);
}

// One triangle at z = 1: (0,0,1), (1,0,1), (0,1,1), and the quad it makes with (1,1,1).
Scene unit_quad() {
  Scene s;
  s.source = "unit quad";
  s.materials.push_back(Material{});
  Mesh mesh;
  mesh.name = "quad";
  mesh.positions = {vec3(0, 0, 1), vec3(1, 0, 1), vec3(0, 1, 1), vec3(1, 1, 1)};
  mesh.triangles = {uvec3(0, 1, 2), uvec3(2, 1, 3)};
  mesh.materials = {0, 0};
  s.meshes.push_back(mesh);
  s.finalize();
  return s;
}

TEST(Bvh, AnalyticHitWithBothFacesAndTheRaysInterval) {
  const Scene scene = unit_quad();
  const auto tracer = make_bvh_tracer(scene);
  const auto embree = make_embree_tracer(scene);
  Ray r{vec3(0.25f, 0.5f, 0.0f), 0.0f, vec3(0.0f, 0.0f, 1.0f)};
  Hit h = tracer->intersect(r);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 0u);
  EXPECT_EQ(h.triangle, 0u);
  EXPECT_FLOAT_EQ(h.t, 1.0f);
  EXPECT_FLOAT_EQ(h.barycentric.x, 0.25f);  // weight of vertex 1 at (1, 0)
  EXPECT_FLOAT_EQ(h.barycentric.y, 0.5f);   // weight of vertex 2 at (0, 1)
  // From behind: the back face is hit too, at the same weights.
  Ray back{vec3(0.25f, 0.5f, 3.0f), 0.0f, vec3(0.0f, 0.0f, -0.5f)};
  h = tracer->intersect(back);
  ASSERT_TRUE(h.valid());
  EXPECT_FLOAT_EQ(h.t, 4.0f);  // in units of the (unnormalised) direction, as Embree
  EXPECT_FLOAT_EQ(h.barycentric.x, 0.25f);
  // The interval: (tmin, tmax], as Embree takes it.
  const std::tuple<float, float, bool> intervals[] = {{0.0f, 0.5f, false},
                                                      {0.0f, 1.0f, true},
                                                      {0.5f, 2.0f, true},
                                                      {1.5f, 9.0f, false},
                                                      {1.0f, 9.0f, false}};
  for (const auto& [tmin, tmax, hit] : intervals) {
    Ray s = r;
    s.tmin = tmin;
    s.tmax = tmax;
    EXPECT_EQ(tracer->intersect(s).valid(), hit) << tmin << " " << tmax;
    EXPECT_EQ(tracer->occluded(s), hit) << tmin << " " << tmax;
    EXPECT_EQ(embree->occluded(s), hit) << "embree " << tmin << " " << tmax;
  }
  // The second triangle, on the far side of the diagonal.
  h = tracer->intersect(Ray{vec3(0.75f, 0.75f, 0.0f), 0.0f, vec3(0.0f, 0.0f, 1.0f)});
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.triangle, 1u);
}

// Rays towards points of the shared diagonal of a tilted quad never fall between its two
// triangles (targets stay clear of the quad's outer corners, where a ray may pass outside).
TEST(Bvh, RaysThroughASharedEdgeHitOneOfItsTriangles) {
  Scene scene = unit_quad();
  scene.meshes[0].transform(glm::rotate(mat4(1.0f), 0.7f, glm::normalize(vec3(1.0f, 2.0f, 0.5f))));
  scene.derive();
  const Bvh bvh(scene);
  const Mesh& m = scene.meshes[0];
  Pcg32 rng(21);
  int misses = 0;
  for (int i = 0; i < 20000; ++i) {
    const float s = 0.01f + 0.98f * rng.next_float();
    const vec3 target = m.positions[1] + s * (m.positions[2] - m.positions[1]);
    Ray r;
    r.origin = target + 3.0f * sample_uniform_sphere(rng.next2());
    r.direction = target - r.origin;
    misses += !bvh_intersect(bvh.view(), r).valid() + !bvh_occluded(bvh.view(), r);
  }
  EXPECT_EQ(misses, 0);
}

TEST(Bvh, SceneWithoutTrianglesHitsNothing) {
  Scene scene;
  scene.source = "empty";
  scene.materials.push_back(Material{});
  Mesh empty;
  empty.name = "empty";
  scene.meshes.push_back(empty);
  scene.lights.push_back(Light::sphere(vec3(0.0f, 0.0f, 2.0f), 0.5f, vec3(1.0f)));
  scene.finalize();
  const auto tracer = make_bvh_tracer(scene);
  EXPECT_EQ(tracer->view().bvh.node_count, 0u);
  const Ray towards{vec3(0.0f), 0.0f, vec3(0.0f, 0.0f, 1.0f)};
  const Ray away{vec3(0.0f), 0.0f, vec3(0.0f, 0.0f, -1.0f)};
  EXPECT_FALSE(tracer->intersect(away).any());
  EXPECT_FALSE(tracer->occluded(away));
  // The sphere light is still there.
  const Hit h = tracer->intersect(towards);
  EXPECT_TRUE(h.sphere_light());
  EXPECT_FLOAT_EQ(h.t, 1.5f);
  EXPECT_TRUE(tracer->occluded(towards));
}

TEST(Bvh, ReportsMemoryAndBuildTime) {
  const Scene scene = make_cubes(500, 3);
  const auto tracer = make_bvh_tracer(scene);
  const TracerStats stats = tracer->stats();
  EXPECT_GE(stats.memory_bytes, scene.triangle_count() * (sizeof(BvhTriangle) + 8));
  EXPECT_GT(stats.build_ms, 0.0);
}

}  // namespace
}  // namespace bounce
