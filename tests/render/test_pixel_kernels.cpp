// The per-pixel kernels on hand-made views: the G-buffer's surface record round trip, a sphere
// light seen by a primary ray, and direct light from a point light with its one shadow ray.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/gbuffer_kernel.h"
#include "bounce/scene/light.h"

namespace bounce {
namespace {

SurfaceHit sample_surface() {
  return {.position = vec3(1.0f, 2.0f, 3.0f),
          .normal = glm::normalize(vec3(0.0f, 1.0f, 0.2f)),
          .geometric_normal = vec3(0.0f, 1.0f, 0.0f),
          .albedo = vec3(0.5f, 0.25f, 0.125f),
          .f0 = vec3(0.04f),
          .emission = vec3(3.0f, 2.0f, 1.0f),
          .roughness = 0.3f};
}

TEST(PixelKernels, GBufferStoresAndReturnsTheSurfaceRecord) {
  GBuffer g;
  g.resize(2, 1);
  const SurfaceHit s = sample_surface();
  g.view().store(1, s);
  const SurfaceHit back = g.surface(1);
  EXPECT_EQ(back.position, s.position);
  EXPECT_EQ(back.normal, s.normal);
  EXPECT_EQ(back.geometric_normal, s.geometric_normal);
  EXPECT_EQ(back.albedo, s.albedo);
  EXPECT_EQ(back.f0, s.f0);
  EXPECT_EQ(back.emission, s.emission);
  EXPECT_EQ(back.roughness, s.roughness);
}

TEST(PixelKernels, SphereLightHitShowsItsRadianceWithoutASurface) {
  const LightRecord light = Light::sphere(vec3(0.0f, 0.0f, 5.0f), 1.0f, vec3(7.0f, 8.0f, 9.0f));
  SceneView scene;
  scene.lights = &light;
  scene.light_count = 1;
  GBuffer g;
  g.resize(1, 1);
  const vec3 forward(0.0f, 0.0f, 1.0f);
  const Ray ray{vec3(0.0f), 0.0f, glm::normalize(vec3(0.0f, 0.6f, 0.8f))};
  Hit hit;
  hit.t = 4.0f;
  hit.light = 0;
  gbuffer_pixel(scene, forward, 0.001f, ray, hit, 0, g.view());
  EXPECT_FALSE(g.hit(0));
  EXPECT_EQ(g.mesh[0], kNoPrimitive);
  EXPECT_EQ(g.emission[0], vec3(7.0f, 8.0f, 9.0f));
  EXPECT_FLOAT_EQ(g.depth[0], 4.0f * 0.8f);
  EXPECT_EQ(g.normal[0], vec3(0.0f));
}

TEST(PixelKernels, PointLightGivesOneShadowRayWithLambertRadiance) {
  // A white Lambert point under a point light 2 m above it, seen from straight above.
  const LightRecord light = Light::point(vec3(0.0f, 2.0f, 0.0f), vec3(8.0f));
  SceneView scene;
  scene.lights = &light;
  scene.light_count = 1;
  GBuffer g;
  g.resize(1, 1);
  g.view().store(0, {.position = vec3(0.0f),
                     .normal = vec3(0.0f, 1.0f, 0.0f),
                     .geometric_normal = vec3(0.0f, 1.0f, 0.0f),
                     .albedo = vec3(0.5f)});
  g.primitive[0] = 0;
  std::vector<Ray> rays;
  std::vector<vec3> radiance;
  direct_pixel(scene, std::as_const(g).view(), 0, vec3(0.0f, 1.0f, 0.0f), DirectSettings{},
               [&](const Ray& r, vec3 l) {
                 rays.push_back(r);
                 radiance.push_back(l);
               });
  ASSERT_EQ(rays.size(), 1u);
  // f * E = (0.5 / pi) * 8 / d^2 at normal incidence, d measured from the shadow ray's origin
  // (offset 1e-4 m off the surface at the origin).
  const float expected = 0.5f / kPi * 8.0f / sqr(2.0f - 1e-4f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(radiance[0][c], expected, 1e-5f * expected);
  EXPECT_NEAR(glm::length(rays[0].direction - vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-5f);
  // The shadow ray stops short of the light and starts off the surface.
  EXPECT_GT(rays[0].origin.y, 0.0f);
  EXPECT_LT(rays[0].origin.y + rays[0].tmax, 2.0f);
  EXPECT_GT(rays[0].origin.y + rays[0].tmax, 2.0f - 1e-3f);
}

}  // namespace
}  // namespace bounce
