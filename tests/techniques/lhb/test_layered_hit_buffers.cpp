// The layered hit buffers and their ray query: analytic cases, Embree on identical rays, overflow
// counting, moving meshes, and that the lists do not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/rng.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/lhb/layered_hit_buffers.h"
#include "bounce/techniques/lhb/lhb_query.h"
#include "bounce/techniques/lhb/lhb_tracer.h"
#include "bounce/trace/tracer.h"
#include "scene/hand_built_scenes.h"
#include "techniques/lhb/surface_rays.h"

namespace bounce {
namespace {

using scene_test::quad_mesh;

// A hand-made set: the six axes, the eight cube diagonals and four directions off every axis.
std::vector<vec3> test_directions() {
  std::vector<vec3> d;
  for (int axis = 0; axis < 3; ++axis)
    for (float s : {1.0f, -1.0f}) {
      vec3 v(0.0f);
      v[axis] = s;
      d.push_back(v);
    }
  for (int k = 0; k < 8; ++k)
    d.push_back(glm::normalize(vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
  for (vec3 v : {vec3(0.3f, 0.8f, -0.5f), vec3(-0.6f, -0.2f, 0.7f), vec3(0.1f, -0.9f, -0.3f),
                 vec3(-0.4f, 0.5f, 0.75f)})
    d.push_back(glm::normalize(v));
  return d;
}

int nearest_brute(const std::vector<vec3>& set, vec3 d) {
  int best = 0;
  for (int i = 1; i < int(set.size()); ++i)
    if (glm::dot(set[size_t(i)], d) > glm::dot(set[size_t(best)], d)) best = i;
  return best;
}

uint32_t global_id(const Scene& s, const Hit& h) {
  return h.valid() ? s.triangle_offsets[h.mesh] + h.triangle : LhbHit::kNone;
}

// Quads facing -z at z = 1, 2, ..., count (each of two triangles), 1 x 1 wide.
Scene stacked_quads(int count) {
  Scene s;
  s.source = "stacked quads";
  s.materials.push_back(Material{});
  for (int k = 0; k < count; ++k)
    s.meshes.push_back(quad_mesh("q", vec3(0, 0, float(k + 1)), vec3(0, 1, 0), vec3(1, 0, 0), 0));
  s.finalize();
  return s;
}

TEST(LayeredHitBuffers, QuadAlongItsAxisIsHitAtItsDistanceFromTheFrontOnly) {
  const Scene s = stacked_quads(1);
  const std::vector<vec3> dirs = {vec3(0, 0, 1), vec3(0, 0, -1)};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 32, .layers = 4});
  const Hit front = lhb.closest_hit({vec3(0.3f, 0.6f, -0.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(front.valid());
  EXPECT_NEAR(front.t, 1.5f, 1e-5f);
  EXPECT_EQ(front.mesh, 0u);
  // Beyond the quad, and through its back face (culled by default), nothing.
  EXPECT_FALSE(lhb.closest_hit({vec3(0.3f, 0.6f, 1.5f), 0.0f, dirs[0]}, 0).valid());
  EXPECT_FALSE(lhb.closest_hit({vec3(0.3f, 0.6f, 2.0f), 0.0f, dirs[1]}, 1).valid());
  // tmax is honoured.
  EXPECT_FALSE(lhb.closest_hit({vec3(0.3f, 0.6f, -0.5f), 0.0f, dirs[0], 1.4f}, 0).valid());
  // Outside the quad's footprint (but inside the buffer's region), nothing.
  EXPECT_FALSE(lhb.closest_hit({vec3(1.04f, 0.5f, 0.0f), 0.0f, dirs[0]}, 0).valid());

  LayeredHitBuffers both;
  both.build(s, dirs, {.size = 32, .layers = 4, .cull_back_faces = false});
  const Hit back = both.closest_hit({vec3(0.3f, 0.6f, 2.0f), 0.0f, dirs[1]}, 1);
  ASSERT_TRUE(back.valid());
  EXPECT_NEAR(back.t, 1.0f, 1e-5f);
  EXPECT_EQ(lhb.stats().static_elements * 2, both.stats().static_elements);
}

// An alpha cut-out leaves holes in the buffers: the nearer quad's right half (alpha 0) lets
// rays through to the quad behind it, as Embree's intersection filter does for traced rays.
TEST(LayeredHitBuffers, AlphaMaskedHolesLeaveNoElements) {
  Scene s = stacked_quads(2);
  Material masked;
  masked.alpha_mode = AlphaMode::kMask;
  masked.alpha_texture = 0;
  s.materials.push_back(masked);
  Texture alpha;
  alpha.width = 2;
  alpha.height = 1;
  alpha.texels = {vec3(1.0f), vec3(0.0f)};
  s.textures.push_back(alpha);
  Mesh& front = s.meshes[0];
  for (const vec3& p : front.positions) front.uvs.push_back({p.x, p.y});
  std::fill(front.materials.begin(), front.materials.end(), 1u);
  s.finalize();

  const std::vector<vec3> dirs = {vec3(0, 0, 1)};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 32, .layers = 4});
  const auto embree = make_embree_tracer(s);
  for (const float x : {0.1f, 0.3f, 0.7f, 0.9f}) {
    const Ray ray{vec3(x, 0.5f, -0.5f), 0.0f, dirs[0]};
    const Hit hit = lhb.closest_hit(ray, 0), traced = embree->intersect(ray);
    ASSERT_TRUE(hit.valid()) << x;
    ASSERT_TRUE(traced.valid()) << x;
    EXPECT_EQ(hit.mesh, x < 0.5f ? 0u : 1u) << x;
    EXPECT_EQ(traced.mesh, hit.mesh) << x;
    EXPECT_NEAR(hit.t, x < 0.5f ? 1.5f : 2.5f, 1e-5f) << x;
  }
}

TEST(LayeredHitBuffers, JitterMovesTheProjectedPositionAcrossTheDirection) {
  const Scene s = stacked_quads(1);
  const std::vector<vec3> dirs = {glm::normalize(vec3(0.2f, -0.1f, 1.0f))};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 64, .layers = 4});
  const LhbView v = lhb.view();
  const vec3 o(0.5f, 0.5f, -0.3f);
  for (vec2 j : {vec2(3.0f, 0.0f), vec2(-2.5f, 4.0f), vec2(0.25f, -7.0f)}) {
    const LhbHit a = lhb_closest(v, 0, o, 0.0f, j);
    const LhbHit b = lhb_closest(v, 0, o + v.frames[0].across(j), 0.0f);
    ASSERT_TRUE(a.valid());
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_NEAR(a.t, b.t, 1e-5f);
    // The hit point lies on the jittered texel's centre line, within a texel's slope of the
    // quad's plane.
    EXPECT_NEAR(a.point.z, 1.0f, 0.25f * lhb.texel_size(0));
  }
}

// Rays through texel centres along every buffer direction, from random depths, against Embree
// with both faces kept (Embree's semantics): the same triangle, at the same distance.
void expect_texel_rays_match_embree(const Scene& s, int rays_per_direction) {
  const std::vector<vec3> dirs = test_directions();
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 96, .layers = 64, .cull_back_faces = false});
  ASSERT_EQ(lhb.stats().dropped_elements, 0u);
  const auto embree = make_embree_tracer(s);
  const float scale = s.bounds.diagonal();
  Pcg32 rng(7);
  int rays = 0, mismatches = 0, hits = 0;
  for (int d = 0; d < int(dirs.size()); ++d) {
    const LhbFrame& f = lhb.frame(d);
    float zlo = INFINITY, zhi = -INFINITY;
    for (int c = 0; c < 8; ++c) {
      const vec3 p(c & 1 ? s.bounds.hi.x : s.bounds.lo.x, c & 2 ? s.bounds.hi.y : s.bounds.lo.y,
                   c & 4 ? s.bounds.hi.z : s.bounds.lo.z);
      zlo = std::min(zlo, f.depth(p));
      zhi = std::max(zhi, f.depth(p));
    }
    for (int k = 0; k < rays_per_direction; ++k) {
      const float x = float(rng.next_below(96)) + 0.5f, y = float(rng.next_below(96)) + 0.5f;
      const float z = zlo + rng.next_float() * (zhi - zlo);
      const vec3 o = (f.u0 + x / f.scale_u) * f.u + (f.v0 + y / f.scale_v) * f.v + z * f.d;
      const Ray ray{o, 1e-4f * scale, dirs[size_t(d)]};
      const Hit want = embree->intersect(ray);
      const Hit got = lhb.closest_hit(ray, d);
      ++rays;
      hits += want.valid();
      const bool same = global_id(s, want) == global_id(s, got) ||
                        (want.valid() && got.valid() && std::abs(want.t - got.t) < 1e-4f * scale);
      if (!same) {
        ++mismatches;
        continue;
      }
      if (want.valid()) {
        EXPECT_NEAR(got.t, want.t, 1e-4f * scale);
      }
    }
  }
  EXPECT_GT(hits, rays / 4);
  // Only texel centres within float rounding of a silhouette edge may differ.
  EXPECT_LE(mismatches, rays / 500) << mismatches << " of " << rays;
}

TEST(LayeredHitBuffers, TexelCentreRaysHitWhatEmbreeHitsOnCornell) {
  expect_texel_rays_match_embree(make_builtin_scene("cornell"), 1000);
}

TEST(LayeredHitBuffers, TexelCentreRaysHitWhatEmbreeHitsOnCubes) {
  expect_texel_rays_match_embree(make_builtin_scene("cubes:300"), 1000);
}

// The gathering case (seed 001 section 5.3): rays leaving surfaces along a buffer direction in
// their upper hemisphere, with the seed's back-face culling. The buffer answers for the texel
// the origin projects into, so a hit may differ near an edge, but it is the same triangle almost
// always, and then at the same depth within a texel's slope.
struct SurfaceRayResult {
  double same_fraction = 0.0;
  double within_texel_fraction = 0.0;  // of the same-triangle hits
};

SurfaceRayResult surface_rays_against_embree(const Scene& s, int size, int count) {
  const std::vector<vec3> dirs = test_directions();
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = size, .layers = 64});
  const auto embree = make_embree_tracer(s);
  const LhbView view = lhb.view();
  Pcg32 rng(11);
  int rays = 0, same = 0, within = 0;
  while (rays < count) {
    const uint32_t m = rng.next_below(uint32_t(s.meshes.size()));
    const std::optional<lhb_test::SurfaceRay> r = lhb_test::draw_surface_ray(s, m, dirs, rng);
    if (!r) continue;
    const int d = r->direction;
    const Hit want = embree->intersect(Ray{r->origin, 0.0f, dirs[size_t(d)]});
    if (!want.valid()) continue;  // leaves the scene
    const LhbHit got = lhb_closest(view, d, r->origin, 0.0f, vec2(0.0f), r->prim);
    ++rays;
    if (got.prim != global_id(s, want)) continue;
    ++same;
    within += std::abs(got.t - want.t) <= lhb.texel_size(d);
  }
  return {double(same) / rays, double(within) / std::max(same, 1)};
}

TEST(LayeredHitBuffers, SurfaceRaysAlongBufferDirectionsHitWhatEmbreeHits) {
  // cubes:300's cubes are a few texels wide at 128 x 128, so more rays end near an edge.
  for (auto [spec, bound] : {std::pair{"cornell", 0.95}, std::pair{"cubes:300", 0.75}}) {
    const Scene s = make_builtin_scene(spec);
    const SurfaceRayResult fine = surface_rays_against_embree(s, 128, 4000);
    EXPECT_GE(fine.same_fraction, bound) << spec;
    EXPECT_GE(fine.within_texel_fraction, 0.97) << spec;
    // The error is the buffers' resolution: coarse buffers miss more.
    const SurfaceRayResult coarse = surface_rays_against_embree(s, 8, 4000);
    EXPECT_LT(coarse.same_fraction, fine.same_fraction) << spec;
  }
}

TEST(LayeredHitBuffers, LhbTracerSnapsEachRayToTheNearestBufferDirection) {
  const Scene s = make_builtin_scene("cornell");
  const std::vector<vec3> dirs = test_directions();
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 64, .layers = 16});
  const LhbTracer tracer(lhb, [&](vec3 d) { return nearest_brute(dirs, d); });
  Pcg32 rng(3);
  std::vector<Ray> rays;
  std::vector<Hit> expected;
  for (int k = 0; k < 500; ++k) {
    const int d = int(rng.next_below(uint32_t(dirs.size())));
    const vec3 o = s.bounds.lo + (s.bounds.hi - s.bounds.lo) *
                                     vec3(rng.next_float(), rng.next_float(), rng.next_float());
    // A small tilt keeps d the nearest direction of the set.
    const vec3 tilted =
        glm::normalize(dirs[size_t(d)] +
                       0.05f * (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f));
    rays.push_back({o, 1e-4f, tilted});
    expected.push_back(lhb.closest_hit({o, 1e-4f, dirs[size_t(d)]}, d));
  }
  std::vector<Hit> got(rays.size());
  tracer.intersect(rays, got);
  int valid = 0;
  for (size_t k = 0; k < rays.size(); ++k) {
    EXPECT_EQ(got[k].mesh, expected[k].mesh);
    EXPECT_EQ(got[k].triangle, expected[k].triangle);
    valid += got[k].valid();
  }
  EXPECT_GT(valid, 100);
}

TEST(LayeredHitBuffers, OverflowKeepsTheNearestLayersAndIsCounted) {
  const Scene s = stacked_quads(20);
  const std::vector<vec3> dirs = {vec3(0, 0, 1)};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 16, .layers = 8});
  const LhbStats st = lhb.stats();
  ASSERT_GT(st.overflow_texels, 0u);
  // Every covered texel receives 20 quads (one triangle each, or two on the diagonal) and keeps 8.
  EXPECT_GE(st.dropped_elements, 12 * st.overflow_texels);
  EXPECT_EQ(st.static_elements, 8 * st.overflow_texels);
  // The nearest 8 are kept: from the front the first quad; behind the 8th, the lists are empty.
  const Hit first = lhb.closest_hit({vec3(0.5f, 0.3f, 0.0f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(first.valid());
  EXPECT_EQ(first.mesh, 0u);
  const Hit eighth = lhb.closest_hit({vec3(0.5f, 0.3f, 7.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(eighth.valid());
  EXPECT_EQ(eighth.mesh, 7u);
  EXPECT_FALSE(lhb.closest_hit({vec3(0.5f, 0.3f, 8.5f), 0.0f, dirs[0]}, 0).valid());

  // With room for all 20 (40 on the diagonal, where both triangles cover the centre) nothing
  // is dropped.
  LayeredHitBuffers roomy;
  roomy.build(s, dirs, {.size = 16, .layers = 48});
  EXPECT_EQ(roomy.stats().dropped_elements, 0u);
  EXPECT_EQ(roomy.stats().overflow_texels, 0u);
  const Hit last = roomy.closest_hit({vec3(0.5f, 0.3f, 19.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(last.valid());
  EXPECT_EQ(last.mesh, 19u);
}

TEST(LayeredHitBuffers, ListsAreSortedAndIndependentOfTheThreadCount) {
  const Scene s = make_builtin_scene("cubes:200");
  const std::vector<vec3> dirs = test_directions();
  LayeredHitBuffers many, one;
  many.build(s, dirs, {.size = 48, .layers = 6});
  {
    const ThreadLimit limit(1);
    one.build(s, dirs, {.size = 48, .layers = 6});
  }
  const LhbView a = many.view(), b = one.view();
  const size_t texels = dirs.size() * 48 * 48;
  size_t elements = 0;
  for (size_t t = 0; t < texels; ++t) {
    ASSERT_EQ(a.static_slab.counts[t], b.static_slab.counts[t]);
    const int n = a.static_slab.kept(t);
    elements += size_t(n);
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(a.static_slab.list(t)[k].prim, b.static_slab.list(t)[k].prim);
      ASSERT_EQ(a.static_slab.list(t)[k].depth, b.static_slab.list(t)[k].depth);
      if (k > 0) {
        ASSERT_LE(a.static_slab.list(t)[k - 1].depth, a.static_slab.list(t)[k].depth);
      }
    }
  }
  EXPECT_EQ(elements, many.stats().static_elements);
  EXPECT_GT(elements, texels / 2);
}

// A floor (static) and a small quad above it (moving), seen from above.
Scene floor_and_tile() {
  Scene s;
  s.source = "floor and tile";
  s.materials.push_back(Material{});
  s.meshes.push_back(quad_mesh("floor", vec3(0, 0, 0), vec3(0, 0, 4), vec3(4, 0, 0), 0));
  s.meshes.push_back(quad_mesh("tile", vec3(1, 1, 1), vec3(0, 0, 1), vec3(1, 0, 0), 0));
  s.finalize();
  return s;
}

void move_mesh(Scene& s, uint32_t m, vec3 by) {
  for (vec3& p : s.meshes[m].positions) p += by;
  s.derive();
}

TEST(LayeredHitBuffers, AMovingMeshChangesTheBuffersInTheNextFrame) {
  Scene s = floor_and_tile();
  const std::vector<vec3> dirs = {vec3(0, -1, 0)};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 64, .layers = 4}, std::vector<uint32_t>{1});
  const Ray down{vec3(1.5f, 3.0f, 1.5f), 0.0f, dirs[0]};
  Hit h = lhb.closest_hit(down, 0);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 1u);
  EXPECT_NEAR(h.t, 2.0f, 1e-4f);
  const LhbStats before = lhb.stats();
  EXPECT_EQ(before.dynamic_triangles, 2u);
  EXPECT_EQ(before.static_triangles, 2u);

  move_mesh(s, 1, vec3(1.5f, 0.0f, 0.0f));
  SceneChange change;
  change.moved_meshes = {1};
  EXPECT_TRUE(lhb.update(s, change));
  h = lhb.closest_hit(down, 0);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 0u);  // the floor, now the tile has gone
  EXPECT_NEAR(h.t, 3.0f, 1e-4f);
  const Hit moved = lhb.closest_hit({vec3(3.0f, 3.0f, 1.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(moved.valid());
  EXPECT_EQ(moved.mesh, 1u);
  // Only the moving slab was redone.
  EXPECT_EQ(lhb.stats().static_builds, before.static_builds);
  EXPECT_EQ(lhb.stats().dynamic_builds, before.dynamic_builds + 1);

  // A camera or light change rebuilds nothing.
  SceneChange camera;
  camera.camera = true;
  camera.lights = true;
  EXPECT_FALSE(lhb.update(s, camera));
}

TEST(LayeredHitBuffers, AMeshThatStartsMovingLeavesTheStaticSlabOnce) {
  Scene s = floor_and_tile();
  const std::vector<vec3> dirs = {vec3(0, -1, 0)};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 64, .layers = 4});
  EXPECT_TRUE(lhb.dynamic_meshes().empty());
  SceneChange change;
  change.moved_meshes = {1};
  move_mesh(s, 1, vec3(0.0f, 0.1f, 0.0f));  // within the region's margin
  lhb.update(s, change);
  EXPECT_EQ(lhb.dynamic_meshes(), std::vector<uint32_t>{1});
  EXPECT_EQ(lhb.stats().static_builds, 2u);
  EXPECT_EQ(lhb.stats().static_triangles, 2u);
  move_mesh(s, 1, vec3(0.0f, 0.1f, 0.0f));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().static_builds, 2u);
  EXPECT_EQ(lhb.stats().dynamic_builds, 2u);
  const Hit h = lhb.closest_hit({vec3(1.5f, 5.0f, 1.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 1u);
  EXPECT_NEAR(h.t, 3.8f, 1e-4f);

  // Moving out of the buffers' region rebuilds everything around the new bounds.
  move_mesh(s, 1, vec3(0.0f, 20.0f, 0.0f));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().static_builds, 3u);
  const Hit far = lhb.closest_hit({vec3(1.5f, 30.0f, 1.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(far.valid());
  EXPECT_EQ(far.mesh, 1u);
  EXPECT_NEAR(far.t, 8.8f, 1e-3f);
}

TEST(LayeredHitBuffers, BadSettingsAndDirectionsAreNamed) {
  const Scene s = stacked_quads(1);
  LayeredHitBuffers lhb;
  const std::vector<vec3> good = {vec3(0, 0, 1)};
  EXPECT_THROW(lhb.build(s, good, {.size = 0}), Error);
  EXPECT_THROW(lhb.build(s, good, {.size = 16, .layers = 0}), Error);
  EXPECT_THROW(lhb.build(s, good, {.size = 16, .layers = 255}), Error);
  EXPECT_THROW(lhb.build(s, std::vector<vec3>{vec3(0, 0, 2)}, {}), Error);
  EXPECT_THROW(lhb.build(s, std::vector<vec3>{}, {}), Error);
  EXPECT_THROW(lhb.build(s, good, {}, std::vector<uint32_t>{5}), Error);
  try {
    lhb.build(s, std::vector<vec3>{vec3(0, 0, 1), vec3(1, 1, 0)}, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("direction 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bounce
