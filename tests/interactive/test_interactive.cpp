// The viewer's window-free pieces: fly camera, resolution scaler, flashlight.
#include <gtest/gtest.h>

#include "bounce/interactive/flashlight.h"
#include "bounce/interactive/fly_camera.h"
#include "bounce/interactive/resolution_scaler.h"
#include "bounce/scene/camera.h"

namespace bounce {
namespace {

void expect_near(vec3 a, vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

Camera cornell_camera() {
  Camera c;
  c.position = vec3(0.278f, 0.273f, -0.800f);
  c.look_at = vec3(0.278f, 0.273f, 0.0f);
  c.vfov_deg = 39.3077f;
  return c;
}

TEST(FlyCamera, KeepsTheSceneCameraAndItsImageAxes) {
  const Camera c = cornell_camera();
  const FlyCamera fly(c);
  const Camera back = fly.camera();
  expect_near(back.position, c.position);
  expect_near(glm::normalize(back.look_at - back.position), vec3(0, 0, 1));
  EXPECT_EQ(back.vfov_deg, c.vfov_deg);
  // The fly camera's right is the image +x of the pipeline's camera rays.
  const CameraRays rays = CameraRays::from(back, 64, 64);
  expect_near(fly.right(), glm::normalize(rays.right));
}

TEST(FlyCamera, MovesAlongItsAxesAndTurnsTowardsTheImageRight) {
  FlyCamera fly(cornell_camera());
  const vec3 start = fly.position();
  const vec3 right = fly.right();
  fly.move(vec3(0.0f, 0.0f, 0.5f));
  expect_near(fly.position(), start + vec3(0.0f, 0.0f, 0.5f));
  fly.move(vec3(1.0f, 2.0f, 0.0f));
  expect_near(fly.position(), start + vec3(0.0f, 2.0f, 0.5f) + right);
  fly.turn(90.0f, 0.0f);
  expect_near(fly.forward(), right);
  fly.turn(0.0f, 200.0f);  // pitch stops short of straight up
  EXPECT_NEAR(fly.pitch_deg(), 89.0f, 1e-3f);
  EXPECT_GT(glm::length(glm::cross(fly.forward(), vec3(0, 1, 0))), 0.01f);
}

TEST(ResolutionScaler, FullResolutionAtRestAndTheTargetInMotion) {
  ResolutionScaler s({33.0, 0.25f, 1.0f, 1.0f / 16.0f});
  EXPECT_EQ(s.update(100.0, false), 1.0f);
  // A frame that costs 4x the target at full resolution: the scale heads for 1/2 (pixels
  // quarter), in steps of 1/16, and never overshoots below the floor.
  float scale = 1.0f;
  for (int i = 0; i < 30; ++i) {
    const double ms = 132.0 * scale * scale;  // frame time proportional to the pixel count
    scale = s.update(ms, true);
    EXPECT_GE(scale, 0.25f);
    EXPECT_EQ(scale * 16.0f, std::floor(scale * 16.0f));
  }
  EXPECT_NEAR(scale, 0.5f, 1.0f / 16.0f + 1e-6f);
  EXPECT_EQ(s.update(10.0, false), 1.0f);  // back at rest: full resolution
  s.settings().target_ms = 0.0;            // scaling off
  EXPECT_EQ(s.update(500.0, true), 1.0f);
  ResolutionScaler floor({10.0, 0.25f, 1.0f, 1.0f / 16.0f});
  for (int i = 0; i < 20; ++i) floor.update(1000.0, true);
  EXPECT_EQ(floor.scale(), 0.25f);
}

TEST(Flashlight, IsASpotAlongTheViewFromNearTheEye) {
  const Camera c = cornell_camera();
  FlashlightSettings fs;
  fs.offset = vec3(0.0f, -0.1f, 0.0f);
  const Light l = make_flashlight(c, fs);
  EXPECT_EQ(l.type, LightType::kSpot);
  EXPECT_EQ(l.name, "flashlight");
  expect_near(l.position, c.position + vec3(0.0f, -0.1f, 0.0f));
  expect_near(l.direction, vec3(0, 0, 1));
  EXPECT_EQ(spot_falloff(l, vec3(0, 0, 1)), 1.0f);
  EXPECT_EQ(spot_falloff(l, glm::normalize(vec3(1, 0, 1))), 0.0f);  // 45 degrees: outside
}

}  // namespace
}  // namespace bounce
