// The flashlight outside the viewer: the camera's spot light lights what the camera faces, in
// the direct and the indirect light, and moves with the camera along a path.
#include <gtest/gtest.h>

#include "bounce/core/error.h"
#include "bounce/interactive/flashlight.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

namespace bounce {
namespace {

// The Cornell box with its ceiling light switched off: the flashlight is the only light.
Scene dark_cornell() {
  Scene scene = load_scene("cornell");
  for (Material& m : scene.materials) m.emission = vec3(0.0f);
  scene.derive();
  scene.lights.clear();
  return scene;
}

float luminance_at(const Image& image, int x, int y) {
  const vec3 c = image.at(x, y);
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// Mean luminance of the central quarter of the image (inside the flashlight's inner cone).
float centre_mean(const Image& image) {
  float sum = 0.0f;
  int n = 0;
  for (int y = image.height() * 3 / 8; y < image.height() * 5 / 8; ++y)
    for (int x = image.width() * 3 / 8; x < image.width() * 5 / 8; ++x, ++n)
      sum += luminance_at(image, x, y);
  return sum / float(n);
}

Camera turned(const Camera& c, float degrees) {
  const float a = glm::radians(degrees);
  const vec3 d = c.look_at - c.position;
  Camera t = c;
  t.look_at = c.position + vec3(std::cos(a) * d.x + std::sin(a) * d.z, d.y,
                                -std::sin(a) * d.x + std::cos(a) * d.z);
  return t;
}

struct Shot {
  Image direct, indirect;
};

// One frame of `vertex` from `camera` with the flashlight placed at `light_camera`.
Shot render_with_flashlight(const Camera& camera, const Camera& light_camera) {
  Scene scene = dark_cornell();
  const size_t index = add_flashlight(scene, scene.camera, FlashlightSettings{});
  place_flashlight(scene, index, light_camera, FlashlightSettings{});
  auto tracer = make_embree_tracer(scene);
  auto technique = make_technique("vertex");
  technique->params().set("photons_from_light", "2000");
  technique->params().set("mesh_refinement", "2000");
  Renderer renderer(scene, *tracer, std::move(technique));
  FrameSettings settings;
  settings.width = 48;
  settings.height = 48;
  settings.denoise = false;
  const Frame& f = renderer.render(camera, settings);
  return {f.direct, f.indirect};
}

TEST(Flashlight, LightsWhatTheCameraFaces) {
  const Camera front = load_scene("cornell").camera;
  const Shot lit = render_with_flashlight(front, front);
  // The back wall ahead: lit directly; the walls beside it by photons off the back wall.
  EXPECT_GT(centre_mean(lit.direct), 0.05f);
  EXPECT_GT(centre_mean(lit.indirect), 0.0f);
  // The corners are outside the 25-degree outer cone: no direct light there.
  EXPECT_EQ(luminance_at(lit.direct, 0, 0), 0.0f);
  EXPECT_EQ(luminance_at(lit.direct, 47, 47), 0.0f);

  // From inside the box, a camera turned 40 degrees to the red wall carries the light with it:
  // the centre stays lit.
  Camera inside = front;
  inside.position.z = 0.15f;
  inside.look_at.z = 1.0f;
  const Camera left = turned(inside, 40.0f);
  const Shot followed = render_with_flashlight(left, left);
  EXPECT_GT(centre_mean(followed.direct), 0.05f);
  // The same view with the light left pointing ahead: the centre is dark in direct light.
  const Shot left_behind = render_with_flashlight(left, inside);
  EXPECT_LT(centre_mean(left_behind.direct), 0.1f * centre_mean(followed.direct));
}

TEST(Flashlight, FollowsTheCameraAlongAPath) {
  Scene scene = dark_cornell();
  CameraPath& path = scene.animation.camera_path;
  path.position.times = {0.0f, 1.0f, 2.0f};
  path.position.values = {vec3(0.278f, 0.273f, -0.8f), vec3(0.45f, 0.3f, -0.6f),
                          vec3(0.2f, 0.25f, -0.5f)};
  path.look_at.times = path.position.times;
  path.look_at.values = {vec3(0.278f, 0.273f, 0.0f), vec3(0.2f, 0.25f, 0.3f),
                         vec3(0.4f, 0.15f, 0.35f)};
  scene.animation.loop = false;
  const FlashlightSettings fs;
  const size_t index = add_flashlight(scene, scene.camera, fs);
  ASSERT_EQ(index, 0u);
  for (float t : {0.0f, 0.4f, 1.0f, 1.7f, 2.0f}) {
    const Camera c = scene.animation.camera_at(scene.camera, t);
    const bool moved = place_flashlight(scene, index, c, fs);
    EXPECT_EQ(moved, t > 0.0f) << "t " << t;  // at t 0 it is where add_flashlight put it
    EXPECT_FALSE(place_flashlight(scene, index, c, fs)) << "t " << t;  // placed: no change
    const Light& l = scene.lights[index];
    const vec3 forward = glm::normalize(c.look_at - c.position);
    EXPECT_NEAR(glm::dot(l.direction, forward), 1.0f, 1e-5f) << "t " << t;
    // Held 5 cm below the eye, across the view.
    EXPECT_NEAR(glm::length(l.position - c.position), 0.05f, 1e-5f) << "t " << t;
    EXPECT_NEAR(glm::dot(l.position - c.position, forward), 0.0f, 1e-5f) << "t " << t;
  }
  // A changed setting moves it too.
  FlashlightSettings brighter = fs;
  brighter.intensity *= 2.0f;
  EXPECT_TRUE(place_flashlight(scene, index, scene.camera, brighter));
  EXPECT_THROW(place_flashlight(scene, 3, scene.camera, fs), Error);
}

}  // namespace
}  // namespace bounce
