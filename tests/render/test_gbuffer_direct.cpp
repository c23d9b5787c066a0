// The renderer's fused pass (build_gbuffer_and_direct: each block's direct light right after its
// G-buffer) against the two stages run one after the other over the whole frame.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/render/direct.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/gbuffer_direct.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/primary_raster.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"

namespace bounce {
namespace {

template <typename T>
void expect_same_bytes(const std::vector<T>& a, const std::vector<T>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(T)), 0) << what;
}

// A size that is not a multiple of the pass's 128 x 32 blocks nor of its tiles, so partial
// blocks and tiles at the right and bottom edges are covered.
// With `rasterise`, both take their primary visibility from the raster (primary_raster.h).
void expect_fused_pass_equals_the_stages(const Scene& scene, bool rows, bool rasterise = false) {
  constexpr int kWidth = 150, kHeight = 70;
  const SceneData data = SceneData::from(scene);
  const std::unique_ptr<Tracer> tracer = make_embree_tracer(scene);
  const LightPicker picker = LightPicker::build(scene);
  const CameraRays camera = CameraRays::from(scene.camera, kWidth, kHeight);
  const vec2 subpixel(0.3f, 0.7f);
  DirectSettings settings;
  settings.light_samples = 2;
  settings.one_shadow_ray = true;
  settings.frame = 5;
  ASSERT_EQ(direct_takes_rows(data.view(), picker.view(), settings), rows);
  PrimaryRaster raster;
  if (rasterise) {
    ASSERT_TRUE(raster.build(data.view(), camera, subpixel, kWidth, kHeight));
  }
  const PrimaryRaster* visibility = rasterise ? &raster : nullptr;

  GBuffer g1;
  g1.resize(kWidth, kHeight);
  Image d1(kWidth, kHeight);
  const uint64_t primary = build_gbuffer(data.view(), *tracer, camera, subpixel, g1, visibility);
  const uint64_t shadow =
      compute_direct(data.view(), picker.view(), *tracer, g1, camera.origin, settings, d1);

  GBuffer g2;
  g2.resize(kWidth, kHeight);
  Image d2(kWidth, kHeight);
  const GBufferAndDirect fused =
      build_gbuffer_and_direct(data.view(), picker.view(), *tracer, camera, subpixel, settings, g2,
                               d2, nullptr, {}, visibility);

  EXPECT_EQ(fused.primary_rays, primary);
  EXPECT_EQ(fused.shadow_rays, shadow);
  EXPECT_GT(shadow, 0u);
  EXPECT_GE(fused.gbuffer_ms, 0.0);
  EXPECT_GE(fused.direct_ms, 0.0);
  expect_same_bytes(g1.position, g2.position, "position");
  expect_same_bytes(g1.normal, g2.normal, "normal");
  expect_same_bytes(g1.geometric_normal, g2.geometric_normal, "geometric normal");
  expect_same_bytes(g1.albedo, g2.albedo, "albedo");
  expect_same_bytes(g1.roughness, g2.roughness, "roughness");
  expect_same_bytes(g1.f0, g2.f0, "f0");
  expect_same_bytes(g1.emission, g2.emission, "emission");
  expect_same_bytes(g1.depth, g2.depth, "depth");
  expect_same_bytes(g1.primitive, g2.primitive, "primitive");
  expect_same_bytes(g1.mesh, g2.mesh, "mesh");
  expect_same_bytes(g1.barycentric, g2.barycentric, "barycentric");
  expect_same_bytes(d1.pixels(), d2.pixels(), "direct light");
  double lit = 0.0;
  for (const vec3& p : d2.pixels()) lit += double(p.x + p.y + p.z);
  EXPECT_GT(lit, 1.0) << "the box is lit";
}

TEST(GBufferAndDirect, EqualsTheTwoStagesWithTheRowLoop) {
  Scene s = make_cornell();
  s.lights.push_back(Light::spot(vec3(0.3f, 0.5f, 0.2f), vec3(0, -1, 0), vec3(2.0f), 20, 30));
  s.finalize();
  expect_fused_pass_equals_the_stages(s, /*rows=*/true);
  expect_fused_pass_equals_the_stages(s, /*rows=*/true, /*rasterise=*/true);
}

TEST(GBufferAndDirect, EqualsTheTwoStagesPixelByPixel) {
  Scene s = make_cornell();  // a sphere light: the per-pixel kernel
  s.lights.push_back(Light::sphere(vec3(0.3f, 0.4f, 0.3f), 0.05f, vec3(1.0f)));
  s.finalize();
  expect_fused_pass_equals_the_stages(s, /*rows=*/false);
  expect_fused_pass_equals_the_stages(s, /*rows=*/false, /*rasterise=*/true);
}

}  // namespace
}  // namespace bounce
