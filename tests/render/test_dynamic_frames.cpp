// Dynamic scenes through the frame pipeline: an edit or an animation step shows in the very next
// frame for every technique, the tracer follows moved geometry, and averaging at rest restarts.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "bounce/core/color.h"
#include "bounce/eval/render_image.h"
#include "bounce/render/light_change_region.h"
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

// The Cornell box with a spot light above its tall block aimed at its left wall (x = 0) along
// kWall, the scene's last light; the cone's inner and outer angles in degrees.
const vec3 kWall(-1.0f, 0.0f, 0.0f);
Scene cornell_with_wall_spot(float inner_deg, float outer_deg) {
  Scene scene = make_cornell();
  scene.lights.push_back(
      Light::spot(vec3(0.278f, 0.45f, 0.28f), kWall, vec3(0.2f), inner_deg, outer_deg));
  scene.derive();
  return scene;
}

// Real-time frames of `size` x `size` pixels with the denoiser's history: one light sample.
FrameSettings denoised_frame(int size) {
  FrameSettings settings = small_frame();
  settings.width = settings.height = size;
  settings.light_samples = 1;
  settings.accumulate = true;
  settings.denoise = true;
  return settings;
}

// Aims cornell_with_wall_spot's spot at frame k of a sweep across the wall, 3 degrees a frame.
void sweep(Light& spot, int k) {
  const float turn = glm::radians(-24.0f + 3.0f * float(k));
  spot.direction =
      vec3(glm::rotate(glm::mat4(1.0f), turn, vec3(0.0f, 1.0f, 0.0f)) * vec4(kWall, 0.0f));
}

// The direct light of `scene` seen from its camera in `settings`' size, converged: eight frames
// of 256 samples a light, averaged.
Image converged_direct(const Scene& scene, FrameSettings settings) {
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  settings.denoise = false;
  settings.accumulate = true;
  settings.light_samples = 256;
  for (int k = 0; k < 7; ++k) renderer.render(scene.camera, settings);
  return renderer.render(scene.camera, settings).direct;
}

// A spot light turning to and fro on the Cornell box's left wall under a still camera: the
// ceiling light's direct light everywhere else keeps averaging frame after frame as it does at
// rest, since the change of lights reaches only the spot's cones (light_change_region). Clipping
// every pixel's history to its noisy neighbourhood, as any other change of the world does, would
// keep that light about as noisy as a few frames' average.
TEST(DynamicFrames, ATurningSpotLeavesTheOtherLightsAveraging) {
  // No surface with x > 0.2 is in its cone.
  Scene scene = cornell_with_wall_spot(8.0f, 12.0f);
  const size_t spot = scene.lights.size() - 1;
  const FrameSettings settings = denoised_frame(32);
  const int frames = 24;
  // Mean absolute luminance error of `image` against `reference` over the pixels whose surface
  // lies at x > 0.2, which the spot never lights.
  const auto error_away = [&](const Image& image, const Image& reference, const GBuffer& g) {
    double sum = 0.0;
    int count = 0;
    for (size_t i = 0; i < g.size(); ++i) {
      if (!g.hit(i) || g.position[i].x <= 0.2f) continue;
      sum += std::abs(luminance(image.pixels()[i]) - luminance(reference.pixels()[i]));
      ++count;
    }
    EXPECT_GT(count, 300);
    return sum / std::max(count, 1);
  };
  const auto last_frame = [&](bool turning) {
    scene.lights[spot].direction = kWall;
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique("direct"));
    renderer.denoiser().settings().spatial = false;  // the history alone
    for (int k = 0; k + 1 < frames; ++k) {
      renderer.render(scene.camera, settings);
      if (turning) {
        const float turn = glm::radians(k % 2 == 0 ? 3.0f : -3.0f);
        scene.lights[spot].direction =
            vec3(glm::rotate(glm::mat4(1.0f), turn, vec3(0.0f, 1.0f, 0.0f)) * vec4(kWall, 0.0f));
        renderer.scene_changed(SceneChange{{}, true, false});
      }
    }
    const Frame& f = renderer.render(scene.camera, settings);
    return std::pair<Image, GBuffer>(f.direct, f.gbuffer);
  };
  const auto [rest, g] = last_frame(false);
  const auto [turning, g_turning] = last_frame(true);
  // Pixel centres, as the frames above sample them (render_image's frames are jittered).
  scene.lights[spot].direction = kWall;
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  FrameSettings one = settings;
  one.accumulate = one.denoise = false;
  const Image single = renderer.render(scene.camera, one).direct;
  FrameSettings many = one;
  many.light_samples = 256;
  many.accumulate = true;
  for (int k = 0; k < 7; ++k) renderer.render(scene.camera, many);
  const Image reference = renderer.render(scene.camera, many).direct;
  const double e_rest = error_away(rest, reference, g);
  const double e_turning = error_away(turning, reference, g_turning);
  const double e_single = error_away(single, reference, g);
  EXPECT_LT(e_turning, 1.2 * e_rest) << e_rest << " " << e_single;
  EXPECT_LT(e_turning, 0.25 * e_single) << e_rest << " " << e_single;
}

// A spot light sweeping across the Cornell box's left wall under a still camera, frame after
// frame: shaded apart (FrameSettings::moving_lights_apart), its beam in the displayed frame is
// where the spot points now. Averaged into the denoiser's history with the other lights, the
// history inside its cones is clipped and kept two frames, and the beam lags and smears.
TEST(DynamicFrames, AMovingSpotIsShownWhereItIs) {
  Scene scene = cornell_with_wall_spot(18.0f, 25.0f);
  const size_t spot = scene.lights.size() - 1;
  const FrameSettings settings = denoised_frame(64);
  const int frames = 16;
  const auto aim = [&](int k) { sweep(scene.lights[spot], k); };
  const auto last_frame = [&](bool apart) {
    aim(0);
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique("direct"));
    FrameSettings s = settings;
    s.moving_lights_apart = apart;
    for (int k = 0; k + 1 < frames; ++k) {
      renderer.render(scene.camera, s);
      aim(k + 1);
      renderer.scene_changed(SceneChange{{}, true, false});
    }
    const Frame& f = renderer.render(scene.camera, s);
    return std::pair<Image, GBuffer>(f.direct, f.gbuffer);
  };
  const auto [apart, g] = last_frame(true);
  const auto [in_history, g_history] = last_frame(false);
  const Image reference = converged_direct(scene, settings);  // the last pose
  // Mean absolute luminance error where the beam is or was two frames before.
  const Light now = scene.lights[spot];
  aim(frames - 3);
  const Light before = scene.lights[spot];
  const auto in_beam = [&](const Light& l, vec3 p) {
    return in_cone(p, l.position, glm::normalize(l.direction), l.cos_outer);
  };
  const auto error_on_wall = [&](const Image& image, const GBuffer& gb) {
    double sum = 0.0;
    int count = 0;
    for (size_t i = 0; i < gb.size(); ++i) {
      if (!gb.hit(i) || !(in_beam(now, gb.position[i]) || in_beam(before, gb.position[i])))
        continue;
      sum += std::abs(luminance(image.pixels()[i]) - luminance(reference.pixels()[i]));
      ++count;
    }
    EXPECT_GT(count, 100);
    return sum / std::max(count, 1);
  };
  const double e_apart = error_on_wall(apart, g), e_history = error_on_wall(in_history, g_history);
  EXPECT_LT(e_apart, 0.5 * e_history) << e_apart << " " << e_history;
}

// The same spot sweeping for nine frames, then still: the frame of its last move and the two
// after it show its beam as brightly as its converged light. Its light is back in the denoiser's
// history, which did not hold it while it moved: the history in its cone is clipped to the frame
// that stops, as after a change of lights, rather than averaged from nothing over the frames
// before.
TEST(DynamicFrames, ASpotThatStopsMovingStaysLit) {
  Scene scene = cornell_with_wall_spot(18.0f, 25.0f);
  const size_t spot = scene.lights.size() - 1;
  const FrameSettings settings = denoised_frame(64);
  const auto aim = [&](int k) { sweep(scene.lights[spot], k); };
  aim(0);
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  for (int k = 0; k < 8; ++k) {
    renderer.render(scene.camera, settings);
    aim(k + 1);
    renderer.scene_changed(SceneChange{{}, true, false});
  }
  std::vector<Image> still;
  for (int k = 0; k < 3; ++k) still.push_back(renderer.render(scene.camera, settings).direct);
  const GBuffer g = renderer.render(scene.camera, settings).gbuffer;
  const Image reference = converged_direct(scene, settings);
  const Light l = scene.lights[spot];
  for (size_t f = 0; f < still.size(); ++f) {
    double got = 0.0, want = 0.0;
    for (size_t i = 0; i < g.size(); ++i)
      if (g.hit(i) &&
          in_cone(g.position[i], l.position, glm::normalize(l.direction), l.cos_inner)) {
        got += double(luminance(still[f].pixels()[i]));
        want += double(luminance(reference.pixels()[i]));
      }
    EXPECT_GT(want, 0.0);
    // (Without the clip, the frames after the stop show 0.24 and 0.30 of it.)
    EXPECT_NEAR(got / want, 1.0, 0.2) << "frame " << f;
  }
}

// A bright spot sweeping across the left wall of a Cornell box with eight more point lights, so
// that direct light resamples candidates drawn by power (resamples_lights): the spot, shaded
// apart, takes none of the candidates, and the other lights' light away from its beam is the
// same as with the spot dark. (Drawn as a candidate and discarded, it cost the other lights the
// candidates it drew: 115 of these 564 pixels came out the same.)
TEST(DynamicFrames, ALightSetApartTakesNoCandidatesFromTheOthers) {
  const auto last_frame = [](vec3 intensity) {
    Scene scene = cornell_with_wall_spot(8.0f, 12.0f);
    for (int k = 0; k < 8; ++k)
      scene.lights.insert(scene.lights.begin(),
                          Light::point(vec3(0.1f + 0.05f * float(k), 0.4f, 0.2f), vec3(0.002f)));
    scene.lights.back().intensity = intensity;
    scene.derive();
    const size_t spot = scene.lights.size() - 1;
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, make_technique("direct"));
    FrameSettings settings = denoised_frame(32);
    settings.view = DenoiseView::kRaw;  // the frame's direct light as the pass made it
    EXPECT_TRUE(resamples_lights(LightPicker::build(scene).view(), direct_settings(settings, 0)));
    for (int k = 0; k < 4; ++k) {
      sweep(scene.lights[spot], k);
      renderer.scene_changed(SceneChange{{}, true, false});
      renderer.render(scene.camera, settings);
    }
    sweep(scene.lights[spot], 4);
    renderer.scene_changed(SceneChange{{}, true, false});
    const Frame& f = renderer.render(scene.camera, settings);
    Image raw;
    renderer.denoiser().debug_view(DenoiseView::kRaw, raw);
    return std::pair<Image, GBuffer>(raw, f.gbuffer);
  };
  const auto [lit, g] = last_frame(vec3(2.0f));
  const auto [dark, g_dark] = last_frame(vec3(0.0f));
  int count = 0, equal = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (!g.hit(i) || g.position[i].x <= 0.2f) continue;  // the spot's cones never reach there
    const float a = luminance(lit.pixels()[i]), b = luminance(dark.pixels()[i]);
    ++count;
    equal += std::abs(a - b) <= 1e-5f * (1.0f + b);
  }
  EXPECT_GT(count, 300);
  EXPECT_EQ(equal, count);
}

}  // namespace
}  // namespace bounce
