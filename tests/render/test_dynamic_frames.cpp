// Dynamic scenes through the frame pipeline: an edit or an animation step shows in the very next
// frame for every technique, the tracer follows moved geometry, and averaging at rest restarts.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "bounce/core/color.h"
#include "bounce/eval/render_image.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
#include "scene/hand_built_scenes.h"

namespace bounce {
namespace {

FrameSettings small_frame() {
  FrameSettings s;
  s.width = 32;
  s.height = 32;
  s.light_samples = 4;
  return s;
}

float mean_luminance(const Image& image) {
  double sum = 0.0;
  for (const vec3& p : image.pixels()) sum += luminance(p);
  return float(sum / double(image.pixel_count()));
}

// Lowers the Cornell box's ceiling light by `dy` metres (a mesh of its own).
SceneChange lower_light(Scene& scene, float dy) {
  for (uint32_t i = 0; i < scene.meshes.size(); ++i)
    if (scene.meshes[i].name == "light") {
      for (vec3& p : scene.meshes[i].positions) p.y -= dy;
      scene.derive();
      return SceneChange{{i}, true, false};
    }
  ADD_FAILURE() << "the Cornell box has no mesh named 'light'";
  return {};
}

TEST(DynamicFrames, EveryTechniqueShowsAMovedLightInTheNextFrame) {
  for (const std::string& name : technique_names()) {
    SCOPED_TRACE(name);
    Scene scene = make_cornell();
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique(name));
    FrameSettings settings = small_frame();
    settings.accumulate = true;
    for (int i = 0; i < 3; ++i) renderer.render(scene.camera, settings);
    const float before = mean_luminance(renderer.render(scene.camera, settings).color);
    renderer.scene_changed(lower_light(scene, 0.15f));
    const Frame& after = renderer.render(scene.camera, settings);
    EXPECT_EQ(after.frames_averaged, 1);  // averaging restarted
    // The same frame from a pipeline built on the moved scene.
    auto fresh_tracer = make_embree_tracer(scene);
    Renderer fresh(scene, *fresh_tracer, make_technique(name));
    const float expected = mean_luminance(fresh.render(scene.camera, settings).color);
    const float got = mean_luminance(after.color);
    // A light lower in the box changes the picture a lot...
    EXPECT_GT(std::abs(expected - before), 0.2f * before);
    // ... and the first frame after the move already shows it (up to per-frame noise).
    EXPECT_NEAR(got, expected, 0.1f * expected);
  }
}

TEST(DynamicFrames, TheTracerFollowsAnAnimatedMesh) {
  // A unit quad facing the camera slides across the view; the G-buffer sees it where it is.
  Scene s;
  s.source = "slider";
  s.materials.push_back(Material{});
  // Faces -z, towards the camera.
  s.meshes.push_back(
      scene_test::quad_mesh("quad", vec3(-0.5f, -0.5f, 0), vec3(0, 1, 0), vec3(1, 0, 0), 0));
  s.lights.push_back(Light::point(vec3(0, 0, -2), vec3(1.0f)));
  TrsTrack slide;
  slide.name = "slide";
  slide.translation.times = {0.0f, 1.0f};
  slide.translation.values = {vec3(0.0f), vec3(3.0f, 0.0f, 0.0f)};
  s.animation.tracks = {slide};
  s.animation.meshes = {AnimatedMesh{0, {0}, {}, {}}};
  s.animation.loop = false;
  s.camera.position = vec3(0, 0, -4);
  s.camera.look_at = vec3(0, 0, 0);
  s.camera.vfov_deg = 90.0f;
  s.has_camera = true;
  s.finalize();
  auto tracer = make_embree_tracer(s);
  Renderer renderer(s, *tracer, make_technique("direct"));
  const FrameSettings settings = small_frame();
  const CameraRays rays = CameraRays::from(s.camera, settings.width, settings.height);
  const auto hit_at = [&](vec3 world) {
    const vec2 px = rays.project(world);
    const Frame& f = renderer.render(s.camera, settings);
    return f.gbuffer.hit(size_t(px.y) * size_t(settings.width) + size_t(px.x));
  };
  EXPECT_TRUE(hit_at(vec3(0.0f)));
  EXPECT_FALSE(hit_at(vec3(3.0f, 0.0f, 0.0f)));
  for (float t : {0.5f, 1.0f}) renderer.scene_changed(animate(s, t));
  EXPECT_FALSE(hit_at(vec3(0.0f)));
  EXPECT_TRUE(hit_at(vec3(3.0f, 0.0f, 0.0f)));
}

TEST(DynamicFrames, DirectLightAveragesAtRestAndRestartsOnAChange) {
  Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  FrameSettings settings = small_frame();
  settings.light_samples = 1;
  settings.accumulate = true;
  settings.jitter = true;
  // Averaging N one-sample frames removes noise: the averaged image is nearer a 64-sample one.
  for (int i = 1; i <= 16; ++i)
    EXPECT_EQ(renderer.render(scene.camera, settings).frames_averaged, i);
  const Image averaged = renderer.render(scene.camera, settings).direct;
  Camera moved = scene.camera;
  moved.position.x += 0.01f;
  EXPECT_EQ(renderer.render(moved, settings).frames_averaged, 1);
  EXPECT_EQ(renderer.render(moved, settings).frames_averaged, 2);
  renderer.scene_changed(SceneChange{{}, true, false});
  EXPECT_EQ(renderer.render(moved, settings).frames_averaged, 1);

  auto reference_tracer = make_embree_tracer(scene);
  FrameSettings many = small_frame();
  many.light_samples = 64;
  const Image reference = render_image(scene, "direct", many, 16);
  Renderer single(scene, *reference_tracer, make_technique("direct"));
  FrameSettings one = settings;
  one.accumulate = false;
  const Image single_frame = single.render(scene.camera, one).direct;
  double err_avg = 0.0, err_one = 0.0;
  for (size_t i = 0; i < reference.pixel_count(); ++i) {
    err_avg += std::abs(luminance(averaged.pixels()[i]) - luminance(reference.pixels()[i]));
    err_one += std::abs(luminance(single_frame.pixels()[i]) - luminance(reference.pixels()[i]));
  }
  EXPECT_LT(err_avg, 0.5 * err_one);
}

}  // namespace
}  // namespace bounce
