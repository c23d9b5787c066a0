// The built-in Cornell box renders as the measured box should look under direct light.
#include <gtest/gtest.h>

#include "bounce/core/color.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

namespace bounce {
namespace {

constexpr int kSize = 96;

struct CornellFrame {
  Scene scene = make_cornell();
  Image image;
  GBuffer gbuffer;

  CornellFrame() {
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique("direct"));
    FrameSettings settings;
    settings.width = settings.height = kSize;
    settings.light_samples = 32;
    const Frame& f = renderer.render(scene.camera, settings);
    image = f.color;
    gbuffer = f.gbuffer;
  }
  vec3 at_world(vec3 p, int radius = 2) const {
    const vec2 px = CameraRays::from(scene.camera, kSize, kSize).project(p);
    return mean(image, int(px.x) - radius, int(px.y) - radius, int(px.x) + radius + 1,
                int(px.y) + radius + 1);
  }
};

const CornellFrame& cornell() {
  static const CornellFrame frame;
  return frame;
}

TEST(Cornell, RedWallOnTheLeftGreenWallOnTheRight) {
  const Image& image = cornell().image;
  const vec3 left = mean(image, 0, 0, kSize / 3, kSize);
  const vec3 right = mean(image, kSize - kSize / 3, 0, kSize, kSize);
  EXPECT_GT(left.x, left.y);
  EXPECT_GT(left.x, left.z);
  EXPECT_GT(right.y, right.x);
  EXPECT_GT(right.y, right.z);
}

TEST(Cornell, CeilingLightIsTheBrightestRegion) {
  const CornellFrame& c = cornell();
  float light_sum = 0.0f, brightest_other = 0.0f;
  int light_pixels = 0;
  for (size_t i = 0; i < c.gbuffer.size(); ++i) {
    const float y = luminance(c.image.pixels()[i]);
    if (max_component(c.gbuffer.emission[i]) > 0.0f) {
      light_sum += y;
      ++light_pixels;
    } else {
      brightest_other = std::max(brightest_other, y);
    }
  }
  ASSERT_GT(light_pixels, 4);
  EXPECT_GT(light_sum / light_pixels, brightest_other);
  // Its pixels show the emitted radiance (17, 12, 4) exactly.
  const vec3 centre = c.at_world(vec3(0.278f, 0.5487f, 0.2795f), 0);
  EXPECT_NEAR(centre.x, 17.0f, 1e-3f);
  EXPECT_NEAR(centre.y, 12.0f, 1e-3f);
  EXPECT_NEAR(centre.z, 4.0f, 1e-3f);
}

TEST(Cornell, FloorUnderTheLightIsBrighterThanTheFrontCorners) {
  const CornellFrame& c = cornell();
  // The visible floor within 15 cm (horizontally) of the point below the light's centre.
  const uint32_t floor_begin = c.scene.triangle_offsets[0];
  ASSERT_EQ(c.scene.meshes[0].name, "floor");
  float sum = 0.0f;
  int count = 0;
  for (size_t i = 0; i < c.gbuffer.size(); ++i) {
    const uint32_t prim = c.gbuffer.primitive[i];
    if (prim < floor_begin || prim >= floor_begin + c.scene.meshes[0].triangle_count()) continue;
    const vec3 p = c.gbuffer.position[i];
    if (glm::length(vec2(p.x, p.z) - vec2(0.278f, 0.2795f)) > 0.15f) continue;
    sum += luminance(c.image.pixels()[i]);
    ++count;
  }
  ASSERT_GT(count, 10);
  const float under = sum / count;
  const float left_corner = luminance(c.at_world(vec3(0.52f, 0.0f, 0.03f)));
  const float right_corner = luminance(c.at_world(vec3(0.03f, 0.0f, 0.03f)));
  EXPECT_GT(under, 1.5f * left_corner);
  EXPECT_GT(under, 1.5f * right_corner);
  EXPECT_GT(left_corner, 0.0f);
}

}  // namespace
}  // namespace bounce
