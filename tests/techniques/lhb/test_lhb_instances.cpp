// Moving meshes as instances: the affine fit that recognises a mesh's motion, and buffers of the
// mesh's own that follow it by a transform, checked against Embree on the moved scene and
// against the stale buffers a missing re-pose would leave.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bounce/core/rng.h"
#include "bounce/scene/animation.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/lhb/affine_pose.h"
#include "bounce/techniques/lhb/direction_sets.h"
#include "bounce/techniques/lhb/layered_hit_buffers.h"
#include "bounce/techniques/lhb/lhb_query.h"
#include "bounce/trace/ray.h"
#include "bounce/trace/tracer.h"
#include "scene/hand_built_scenes.h"
#include "techniques/lhb/surface_rays.h"

namespace bounce {
namespace {

using scene_test::bumpy_ball;
using scene_test::quad_mesh;

mat4 trs(vec3 t, float degrees, vec3 axis, vec3 scale) {
  mat4 m = glm::translate(mat4(1.0f), t);
  m = glm::rotate(m, glm::radians(degrees), glm::normalize(axis));
  return glm::scale(m, scale);
}

vec3 apply(const mat4& m, vec3 p) {
  return vec3(m * vec4(p, 1.0f));
}

TEST(AffinePose, RecoversAKeyframeTransformAndRejectsADeformation) {
  Pcg32 rng(3);
  std::vector<vec3> rest;
  for (int i = 0; i < 60; ++i)
    rest.push_back(vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f - vec3(1.0f));
  const std::optional<AffineAnchors> anchors = AffineAnchors::choose(rest);
  ASSERT_TRUE(anchors.has_value());
  EXPECT_FALSE(anchors->flat);
  const mat4 m = trs(vec3(3, -1, 2), 70.0f, vec3(1, 2, 0.5f), vec3(1.3f, 0.8f, 1.1f));
  std::vector<vec3> now;
  for (vec3 p : rest) now.push_back(apply(m, p));
  const std::optional<Affine> fit = fit_affine(*anchors, rest, now);
  ASSERT_TRUE(fit.has_value());
  for (vec3 q : {vec3(5, 0, 0), vec3(-2, 7, 1)})
    for (int c = 0; c < 3; ++c) EXPECT_NEAR((*fit)(q)[c], apply(m, q)[c], 1e-4f);
  // One vertex off by 1% of the size: not an affine motion.
  now[17] += vec3(0.02f, 0.0f, 0.0f);
  EXPECT_FALSE(fit_affine(*anchors, rest, now).has_value());
  // Far from the origin, float rounding is not a deformation: a 2-unit cloud 5 km out.
  std::vector<vec3> far_rest, far_now;
  const mat4 far = trs(vec3(5000, 20, -3000), 25.0f, vec3(0, 1, 0), vec3(1.0f));
  for (vec3 p : rest) {
    far_rest.push_back(p + vec3(5000, 0, -3000));
    far_now.push_back(apply(far, p));
  }
  const std::optional<AffineAnchors> far_anchors = AffineAnchors::choose(far_rest);
  ASSERT_TRUE(far_anchors.has_value());
  EXPECT_TRUE(fit_affine(*far_anchors, far_rest, far_now).has_value());
  // A different vertex count is no motion of this mesh.
  now.pop_back();
  EXPECT_FALSE(fit_affine(*anchors, rest, now).has_value());
}

TEST(AffinePose, AFlatMeshFollowsARotationScaleAndTranslation) {
  const std::vector<vec3> rest = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(2, 0, 1), vec3(0, 0, 1),
                                  vec3(1, 0, 0.5f)};
  const std::optional<AffineAnchors> anchors = AffineAnchors::choose(rest);
  ASSERT_TRUE(anchors.has_value());
  EXPECT_TRUE(anchors->flat);
  const mat4 m = trs(vec3(0.5f, 2, -1), 40.0f, vec3(0, 1, 1), vec3(1.5f));
  std::vector<vec3> now;
  for (vec3 p : rest) now.push_back(apply(m, p));
  const std::optional<Affine> fit = fit_affine(*anchors, rest, now);
  ASSERT_TRUE(fit.has_value());
  // Off the plane too: the normal stands in for the missing fourth vertex.
  for (vec3 q : {vec3(1, 1, 0), vec3(0.3f, -2, 0.7f)})
    for (int c = 0; c < 3; ++c) EXPECT_NEAR((*fit)(q)[c], apply(m, q)[c], 1e-4f);
  // A line determines no map.
  EXPECT_FALSE(AffineAnchors::choose(std::vector<vec3>{vec3(0), vec3(1, 0, 0), vec3(3, 0, 0)}));
  EXPECT_FALSE(AffineAnchors::choose(std::vector<vec3>{}));
}

// A `side` x `side` floor facing up (mesh 0) and balls above it (meshes 1, 2, ...).
Scene floor_with(float side, std::vector<Mesh> balls) {
  Scene s;
  s.source = "floor and balls";
  s.materials.push_back(Material{});
  s.meshes.push_back(quad_mesh("floor", vec3(0, 0, 0), vec3(0, 0, side), vec3(side, 0, 0), 0));
  for (Mesh& ball : balls) s.meshes.push_back(std::move(ball));
  s.finalize();
  return s;
}

// A 4 x 4 floor and a ball of 512 triangles above it.
Scene floor_and_ball() {
  return floor_with(4.0f, {bumpy_ball(16, vec3(1.5f, 1.0f, 1.5f), 0.6f)});
}

void pose(Scene& s, uint32_t m, const std::vector<vec3>& rest, const mat4& by) {
  for (size_t i = 0; i < rest.size(); ++i) s.meshes[m].positions[i] = apply(by, rest[i]);
  s.derive();
}

TEST(LhbInstances, TheBallIsAnOutwardInstance) {
  const Scene s = floor_and_ball();
  const Mesh& ball = s.meshes[1];
  int outward = 0;
  for (uint32_t t = 0; t < ball.triangles.size(); ++t) {
    const uvec3 i = ball.triangles[t];
    const vec3 c = (ball.positions[i.x] + ball.positions[i.y] + ball.positions[i.z]) / 3.0f;
    outward += glm::dot(ball.face_normal_area2(t), c - vec3(1.5f, 1.0f, 1.5f)) > 0.0f;
  }
  EXPECT_GE(outward, int(ball.triangles.size()) - 2 * 16);  // the poles' slivers aside
  LayeredHitBuffers lhb;
  lhb.build(s, DirectionSet::icosahedron(1).directions(), {.size = 32, .layers = 8},
            std::vector<uint32_t>{1});
  EXPECT_EQ(lhb.instance_meshes(), std::vector<uint32_t>{1});
  EXPECT_EQ(lhb.stats().instance_triangles, ball.triangles.size());
  EXPECT_EQ(lhb.stats().dynamic_triangles, 0u);
  // Without instances the ball goes to the moving slab, as the seed does.
  LayeredHitBuffers slab;
  slab.build(s, DirectionSet::icosahedron(1).directions(),
             {.size = 32, .layers = 8, .max_instances = 0}, std::vector<uint32_t>{1});
  EXPECT_TRUE(slab.instance_meshes().empty());
  EXPECT_EQ(slab.stats().dynamic_triangles, ball.triangles.size());
}

// Rays leaving the floor and the ball along buffer directions (their upper hemispheres), against
// Embree on the same scene: of the rays that leave the floor and meet the ball (mesh 1), the
// fraction that meets it within two texels of Embree's distance (the ball's triangles are about
// a texel wide, so the same triangle is a matter of luck at its edges).
double same_triangle_fraction(const Scene& s, const LayeredHitBuffers& lhb,
                              const std::vector<vec3>& dirs, int count, uint32_t seed) {
  const auto embree = make_embree_tracer(s);
  const LhbView view = lhb.view();
  Pcg32 rng(seed);
  int rays = 0, same = 0;
  while (rays < count) {
    const uint32_t m = rng.next_below(4) == 0 ? 1 : 0;
    const std::optional<lhb_test::SurfaceRay> r = lhb_test::draw_surface_ray(s, m, dirs, rng);
    if (!r) continue;
    const int d = r->direction;
    const Hit want = embree->intersect(Ray{r->origin, 0.0f, dirs[size_t(d)]});
    if (!want.valid() || m != 0 || want.mesh != 1) continue;
    const LhbHit got = lhb_closest(view, d, r->origin, 0.0f, vec2(0.0f), r->prim);
    ++rays;
    same += got.valid() && got.prim >= s.triangle_offsets[1] &&
            std::abs(got.t - want.t) <= 2.0f * lhb.texel_size(d);
  }
  return double(same) / double(rays);
}

TEST(LhbInstances, ARigidMoveIsFollowedByATransformWithoutRasterizing) {
  Scene s = floor_and_ball();
  const std::vector<vec3> rest = s.meshes[1].positions;
  const std::vector<vec3> dirs = DirectionSet::icosahedron(2).directions();
  const LhbSettings settings{.size = 64, .layers = 8};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, settings, std::vector<uint32_t>{1});
  const LhbStats built = lhb.stats();
  EXPECT_EQ(built.instances, 1);
  EXPECT_EQ(built.instance_captures, 1u);

  // Stale buffers: what the scene would answer if the move were ignored.
  LayeredHitBuffers stale;
  stale.build(s, dirs, settings, std::vector<uint32_t>{1});

  SceneChange change;
  change.moved_meshes = {1};
  // A translation, a turn about the ball's centre (it stays where it was), and a turn with a
  // scale and a move.
  const vec3 c(1.5f, 1.0f, 1.5f);
  const mat4 to_centre = trs(-c, 0.0f, vec3(0, 1, 0), vec3(1.0f));
  const std::pair<mat4, bool> poses[] = {
      {trs(vec3(0.8f, 0.3f, 0.5f), 0.0f, vec3(0, 1, 0), vec3(1.0f)), true},
      {trs(c, 35.0f, vec3(0.2f, 1, 0), vec3(1.0f)) * to_centre, false},
      {trs(c + vec3(0.5f, 0.3f, 0.4f), 120.0f, vec3(1, 0, 1), vec3(1.3f)) * to_centre, true}};
  for (const auto& [m, moves_away] : poses) {
    pose(s, 1, rest, m);
    ASSERT_TRUE(lhb.update(s, change));
    // The seed's way, for comparison: the ball rasterized again at its new pose.
    LayeredHitBuffers rebuilt;
    rebuilt.build(s, dirs, {.size = 64, .layers = 8, .max_instances = 0}, std::vector<uint32_t>{1});
    const double moved = same_triangle_fraction(s, lhb, dirs, 2000, 5);
    const double seed = same_triangle_fraction(s, rebuilt, dirs, 2000, 5);
    const double ignored = same_triangle_fraction(s, stale, dirs, 2000, 5);
    // As good as rasterizing again: measured 0.956, 0.953 and 0.948 against 0.952, 0.961 and
    // 0.958 (a turned ball is walked along the ray's own direction across the texels of its
    // nearest one; without that walk, 0.907 and 0.876); far better than not following (0.014,
    // 0.124).
    EXPECT_GE(moved, seed - 0.03) << "rebuilt " << seed;
    EXPECT_GE(moved, 0.9);
    if (moves_away) {
      EXPECT_LT(ignored, moved - 0.3) << "moved " << moved;
    }
  }
  const LhbStats after = lhb.stats();
  EXPECT_EQ(after.instance_captures, 1u);  // never rasterized again
  EXPECT_EQ(after.instance_reposes, 3u);
  EXPECT_EQ(after.static_builds, built.static_builds);
  EXPECT_EQ(after.dynamic_builds, built.dynamic_builds);
}

TEST(LhbInstances, AnInstanceMayLeaveTheRegionAndADeformedOneIsCapturedAgain) {
  Scene s = floor_and_ball();
  const std::vector<vec3> rest = s.meshes[1].positions;
  const std::vector<vec3> dirs = {vec3(0, -1, 0), vec3(1, 0, 0)};
  LayeredHitBuffers lhb;
  lhb.build(s, dirs, {.size = 64, .layers = 8}, std::vector<uint32_t>{1});
  SceneChange change;
  change.moved_meshes = {1};

  // Far above the floor, outside the static buffers' region: no rebuild, still hit.
  pose(s, 1, rest, trs(vec3(0, 20, 0), 0.0f, vec3(0, 1, 0), vec3(1.0f)));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().static_builds, 1u);
  Hit h = lhb.closest_hit({vec3(1.5f, 30.0f, 1.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 1u);
  EXPECT_NEAR(h.t, 30.0f - 21.0f - 0.6f, 0.2f);  // the ball's top, bumps and texels aside
  h = lhb.closest_hit({vec3(1.5f, 10.0f, 1.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 0u);  // the floor, where the ball was
  EXPECT_NEAR(h.t, 10.0f, 1e-3f);

  // Squashed to a third of its height: affine, but the texels would stretch 3x (2x is the
  // limit), so it is captured again.
  pose(s, 1, rest, trs(vec3(0), 0.0f, vec3(0, 1, 0), vec3(1.0f, 1.0f / 3.0f, 1.0f)));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().instance_captures, 2u);
  // A deformation: every vertex pushed out along y by its own amount.
  for (vec3& p : s.meshes[1].positions) p.y += 0.3f * p.x * p.x;
  s.derive();
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().instance_captures, 3u);
  const float top = 1.0f / 3.0f + 0.3f * 1.5f * 1.5f;  // roughly: the centre's new height
  h = lhb.closest_hit({vec3(1.5f, 5.0f, 1.5f), 0.0f, dirs[0]}, 0);
  ASSERT_TRUE(h.valid());
  EXPECT_EQ(h.mesh, 1u);
  EXPECT_NEAR(h.t, 5.0f - top - 0.2f, 0.15f);
  // Back to the first pose (not an affine image of the bent one), then mirrored: a mirror
  // swaps front and back faces, so it is captured again rather than re-posed.
  pose(s, 1, rest, mat4(1.0f));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().instance_captures, 4u);
  const uint64_t reposes = lhb.stats().instance_reposes;
  pose(s, 1, rest, trs(vec3(3, 0, 0), 0.0f, vec3(0, 1, 0), vec3(-1.0f, 1.0f, 1.0f)));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().instance_captures, 5u);
  EXPECT_EQ(lhb.stats().instance_reposes, reposes);
  // And an ordinary move after that is a transform again.
  pose(s, 1, rest, trs(vec3(3, 0.5f, 0), 0.0f, vec3(0, 1, 0), vec3(-1.0f, 1.0f, 1.0f)));
  lhb.update(s, change);
  EXPECT_EQ(lhb.stats().instance_captures, 5u);
  EXPECT_EQ(lhb.stats().instance_reposes, reposes + 1);
  EXPECT_EQ(lhb.stats().static_builds, 1u);
}

// Three balls over a floor, of 512, 288 and 128 triangles, each about a third of the floor wide.
Scene floor_and_three_balls() {
  return floor_with(6.0f, {bumpy_ball(16, vec3(1.0f, 1.0f, 1.0f), 0.6f),
                           bumpy_ball(12, vec3(3.0f, 1.0f, 3.0f), 0.6f),
                           bumpy_ball(8, vec3(5.0f, 1.0f, 5.0f), 0.6f)});
}

// A ray straight down over each ball's centre meets that ball, as Embree says.
void expect_each_ball_hit(const Scene& s, const LayeredHitBuffers& lhb) {
  const auto embree = make_embree_tracer(s);
  for (uint32_t m = 1; m < s.meshes.size(); ++m) {
    Bounds b;
    for (const vec3& p : s.meshes[m].positions) b.extend(p);
    const Ray down{vec3(b.centre().x, 8.0f, b.centre().z), 0.0f, vec3(0, -1, 0)};
    const Hit want = embree->intersect(down), got = lhb.closest_hit(down, 0);
    ASSERT_TRUE(got.valid()) << "ball " << m;
    EXPECT_EQ(got.mesh, want.mesh) << "ball " << m;
    EXPECT_NEAR(got.t, want.t, 2.0f * lhb.texel_size(0)) << "ball " << m;
  }
}

TEST(LhbInstances, TheLargestMeshesAreInstancesWithinTheirCountAndTheirTexels) {
  Scene s = floor_and_three_balls();
  const std::vector<vec3> dirs = {vec3(0, -1, 0), vec3(0, 1, 0)};
  const std::vector<uint32_t> moving = {1, 2, 3};
  // At most two instances: the two largest balls; the third shares the moving slab.
  LayeredHitBuffers two;
  two.build(s, dirs, {.size = 64, .layers = 8, .max_instances = 2, .instance_min_triangles = 1},
            moving);
  EXPECT_EQ(two.instance_meshes(), (std::vector<uint32_t>{1, 2}));
  EXPECT_EQ(two.stats().dynamic_triangles, s.meshes[3].triangles.size());
  expect_each_ball_hit(s, two);

  // The three balls grown 4x about the floor's centre, each nearly as wide as the buffers'
  // region: the first instance takes most of one slab's texels, the others do not fit beside it
  // and share the slab.
  std::vector<std::vector<vec3>> rest;
  for (uint32_t m : moving) rest.push_back(s.meshes[m].positions);
  for (size_t k = 0; k < moving.size(); ++k) {
    const vec3 c(2.0f * float(k) + 1.0f, 1.0f, 2.0f * float(k) + 1.0f);
    pose(s, moving[k], rest[k],
         trs(vec3(3, 1, 3), 0.0f, vec3(0, 1, 0), vec3(4.0f)) *
             trs(-c, 0.0f, vec3(0, 1, 0), vec3(1.0f)));
  }
  LayeredHitBuffers big;
  big.build(s, dirs, {.size = 64, .layers = 8, .instance_min_triangles = 1}, moving);
  EXPECT_EQ(big.instance_meshes(), std::vector<uint32_t>{1});
  EXPECT_LE(big.stats().instance_texels, size_t(dirs.size()) * 64u * 64u);
  EXPECT_EQ(big.stats().dynamic_triangles,
            s.meshes[2].triangles.size() + s.meshes[3].triangles.size());

  // Back to their places, all three instances; then ball 1 collapses onto a line, which no
  // instance can hold (it fits no map, and a capture needs a plane): it moves to the slab, and
  // follows there when it comes back.
  for (size_t k = 0; k < moving.size(); ++k) pose(s, moving[k], rest[k], mat4(1.0f));
  LayeredHitBuffers all;
  all.build(s, dirs, {.size = 64, .layers = 8, .instance_min_triangles = 1}, moving);
  EXPECT_EQ(all.instance_meshes(), (std::vector<uint32_t>{1, 2, 3}));
  SceneChange change;
  change.moved_meshes = {1};
  for (vec3& p : s.meshes[1].positions) p = vec3(p.x, 1.0f, 1.0f);
  s.derive();
  all.update(s, change);
  EXPECT_EQ(all.instance_meshes(), (std::vector<uint32_t>{2, 3}));
  EXPECT_EQ(all.stats().dynamic_triangles, s.meshes[1].triangles.size());
  pose(s, 1, rest[0], trs(vec3(0.5f, 0, 0), 0.0f, vec3(0, 1, 0), vec3(1.0f)));
  all.update(s, change);
  expect_each_ball_hit(s, all);
}

TEST(LhbInstances, TheKeyframedBallOfDynamicBallIsReposedAlongItsPath) {
  // scenes/dynamic-ball.bounce.json: a 4,512-triangle ball turning and moving on keyframes in
  // the Cornell box, posed by animate() as the viewer, sequence and bench --animate do.
  Scene s = load_scene(std::string(BOUNCE_SOURCE_DIR) + "/scenes/dynamic-ball.bounce.json");
  ASSERT_EQ(s.animation.meshes.size(), 1u);
  const uint32_t ball = s.animation.meshes[0].mesh;
  animate(s, 0.0f);
  const DirectionSet set = DirectionSet::icosahedron(1);
  LayeredHitBuffers lhb;
  lhb.build(s, set.directions(), {.size = 64, .layers = 8});
  EXPECT_EQ(lhb.instance_meshes(), std::vector<uint32_t>{ball});
  // Sideways at the ball's height, above both blocks (the ceiling is close over it).
  const int across = set.nearest(vec3(1, 0, 0));
  const vec3 d = set.directions()[size_t(across)];
  for (const float t : {0.5f, 1.5f, 2.25f, 3.75f}) {
    const SceneChange change = animate(s, t);
    ASSERT_EQ(change.moved_meshes, std::vector<uint32_t>{ball});
    EXPECT_TRUE(lhb.update(s, change));
    Bounds b;
    for (const vec3& p : s.meshes[ball].positions) b.extend(p);
    // From beside the ball's centre, along the buffer direction nearest to +x.
    const Ray ray{b.centre() - 0.12f * d, 0.0f, d};
    const Hit want = make_embree_tracer(s)->intersect(ray), got = lhb.closest_hit(ray, across);
    ASSERT_TRUE(want.valid() && got.valid()) << t;
    EXPECT_EQ(got.mesh, ball) << t;
    EXPECT_EQ(want.mesh, ball) << t;
    EXPECT_NEAR(got.t, want.t, 2.0f * lhb.texel_size(across)) << t;
  }
  EXPECT_EQ(lhb.stats().instance_captures, 1u);
  EXPECT_EQ(lhb.stats().instance_reposes, 4u);
  EXPECT_EQ(lhb.stats().static_builds, 1u);
}

}  // namespace
}  // namespace bounce
