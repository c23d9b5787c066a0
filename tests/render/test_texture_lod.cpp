// The G-buffer filters textures over each pixel's footprint (ray cones, surface_on's kFiltered):
// a checkerboard of one-texel squares seen with four texels to a pixel reads as its mean grey,
// as the path reference's many samples per pixel average it, where a lookup at the pixel's
// centre reads black, white or a blend of two.
#include <gtest/gtest.h>

#include "bounce/render/gbuffer.h"
#include "bounce/render/primary_raster.h"
#include "bounce/render/surface.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

// The unit quad at z = 0 facing +z, its texture coordinates its x and y, textured with a
// checkerboard of `n` x `n` black and white texels.
Scene checkerboard_quad(int n) {
  Texture t;
  t.name = "checkerboard";
  t.width = t.height = n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) t.texels.push_back(vec3(float((x + y) % 2)));
  return scene_test::textured_unit_quad(t, vec3(1.0f));
}

TEST(TextureLod, APixelSpanningManyTexelsReadsTheirMean) {
  const Scene scene = checkerboard_quad(64);
  const SceneData data = SceneData::from(scene);
  const auto tracer = make_embree_tracer(scene);
  // 1 m away with a 90 degree view over 32 pixels: a pixel spans 1/16 m, four texels, and its
  // centre falls on a texel's centre (half a texel off the quad's centre).
  Camera camera;
  camera.position = vec3(0.5f + 0.5f / 64.0f, 0.5f + 0.5f / 64.0f, 1.0f);
  camera.look_at = vec3(camera.position.x, camera.position.y, 0.0f);
  camera.vfov_deg = 90.0f;
  const CameraRays rays = CameraRays::from(camera, 32, 32);
  EXPECT_NEAR(rays.pixel_spread(), 1.0f / 16.0f, 1e-6f);
  for (const bool rastered : {false, true}) {
    SCOPED_TRACE(rastered ? "raster" : "traced");
    PrimaryRaster raster;
    ASSERT_TRUE(!rastered || raster.build(data.view(), rays, vec2(0.5f), 32, 32));
    GBuffer g;
    g.resize(32, 32);
    build_gbuffer(data.view(), *tracer, rays, vec2(0.5f), g, rastered ? &raster : nullptr);
    int far_from_grey = 0;
    for (int y = 10; y < 22; ++y) {
      for (int x = 10; x < 22; ++x) {
        const size_t i = g.view().index(x, y);
        ASSERT_TRUE(g.hit(i)) << x << "," << y;
        EXPECT_NEAR(g.albedo[i].x, 0.5f, 0.02f) << x << "," << y;
        // The same hit's texel at the point, unfiltered.
        Hit hit;
        hit.mesh = g.mesh[i];
        hit.triangle = g.primitive[i];
        hit.barycentric = g.barycentric[i];
        const vec3 d = glm::normalize(g.position[i] - camera.position);
        far_from_grey += std::abs(surface_at(data.view(), hit, d).albedo.x - 0.5f) > 0.2f;
      }
    }
    EXPECT_GT(far_from_grey, 30);  // a lookup at the point would fail the bound above
  }
}

// Close up, a texel spans many pixels: level 0, the texels themselves, as before. (Far from grey:
// a level of detail too coarse would fail.)
TEST(TextureLod, MagnifiedTexelsAreReadAtThePoint) {
  const Scene scene = checkerboard_quad(4);
  const SceneData data = SceneData::from(scene);
  const auto tracer = make_embree_tracer(scene);
  Camera camera;
  camera.position = vec3(0.5f, 0.5f, 1.0f);
  camera.look_at = vec3(0.5f, 0.5f, 0.0f);
  camera.vfov_deg = 40.0f;
  const CameraRays rays = CameraRays::from(camera, 32, 32);
  GBuffer g;
  g.resize(32, 32);
  build_gbuffer(data.view(), *tracer, rays, vec2(0.5f), g);
  for (size_t i = 0; i < g.size(); ++i) {
    ASSERT_TRUE(g.hit(i));
    Hit hit;
    hit.mesh = g.mesh[i];
    hit.triangle = g.primitive[i];
    hit.barycentric = g.barycentric[i];
    const vec3 d = glm::normalize(g.position[i] - camera.position);
    // (To rounding: the raster's runs evaluate eight pixels at a time, with fused multiply-adds.)
    const vec3 point = surface_at(data.view(), hit, d).albedo;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.albedo[i][c], point[c], 1e-5f) << i;
  }
}

}  // namespace
}  // namespace bounce
