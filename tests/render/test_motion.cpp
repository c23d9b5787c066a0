// Motion vectors (render/motion_kernel.h): still frames have none; a camera move is followed by
// reprojecting each pixel into the previous frame's G-buffer; a moved mesh carries its own motion
// while the rest of the frame stays still; the Renderer fills them frame after frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "bounce/render/gbuffer.h"
#include "bounce/render/motion_kernel.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/scene/scene_edit.h"
#include "bounce/techniques/registry.h"
#include "bounce/trace/tracer.h"

namespace bounce {
namespace {

constexpr int kSize = 64;

GBuffer gbuffer_of(const SceneView& scene, const Tracer& tracer, const CameraRays& rays) {
  GBuffer g;
  g.resize(int(rays.width), int(rays.height));
  build_gbuffer(scene, tracer, rays, vec2(0.5f), g);
  return g;
}

Camera moved_camera(const Camera& c) {
  Camera m = c;
  const vec3 side = glm::normalize(glm::cross(c.look_at - c.position, c.up));
  m.position += 0.03f * side + vec3(0.0f, 0.01f, 0.02f);  // a step aside, up and forward
  m.look_at += 0.02f * side;                              // and a slight turn
  return m;
}

TEST(Motion, StillCameraAndSceneHaveNoMotion) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const SceneData data = SceneData::from(scene);
  const CameraRays rays = CameraRays::from(scene.camera, kSize, kSize);
  GBuffer g = gbuffer_of(data.view(), *tracer, rays);
  compute_motion(data.view(), rays, rays, g);
  for (vec2 m : g.motion) ASSERT_EQ(m, vec2(0.0f));
}

// Each pixel's motion leads back to where its surface point was seen before the camera moved:
// the previous frame's G-buffer, at the reprojected position, holds the same point (up to the
// pixel footprint) wherever that point was visible then.
TEST(Motion, CameraMoveReprojectsOntoTheSameSurfacePoint) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const SceneData data = SceneData::from(scene);
  const CameraRays before = CameraRays::from(scene.camera, kSize, kSize);
  const CameraRays after = CameraRays::from(moved_camera(scene.camera), kSize, kSize);
  const GBuffer previous = gbuffer_of(data.view(), *tracer, before);
  GBuffer current = gbuffer_of(data.view(), *tracer, after);
  compute_motion(data.view(), after, before, current);

  const float footprint = 2.0f * scene.bounds.diagonal() / kSize;
  int checked = 0, agree = 0, moving = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = size_t(y) * kSize + size_t(x);
      if (!current.hit(i)) continue;
      const vec2 m = current.motion[i];
      if (glm::length(m) > 0.5f) ++moving;
      // Centre samples: the point sits at the pixel centre now, so it sat at centre - motion.
      const vec2 q = vec2(float(x) + 0.5f, float(y) + 0.5f) - m;
      const int px = int(std::floor(q.x)), py = int(std::floor(q.y));
      if (px < 0 || py < 0 || px >= kSize || py >= kSize) continue;
      const size_t j = size_t(py) * kSize + size_t(px);
      if (previous.mesh[j] != current.mesh[i]) continue;  // an edge or a disocclusion
      ++checked;
      if (glm::length(previous.position[j] - current.position[i]) < footprint) ++agree;
    }
  EXPECT_GT(moving, kSize * kSize / 2);  // the move is visible
  EXPECT_GT(checked, kSize * kSize / 2);
  EXPECT_GE(agree, checked * 98 / 100);
}

// When only the camera moved, compute_motion takes a row loop (camera_motion_pixel): it gives
// motion_pixel's answer for every pixel, on surfaces, on the sky around the open box, and for
// points behind the previous camera.
TEST(Motion, CameraOnlyRowsEqualThePerPixelKernel) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const SceneData data = SceneData::from(scene);
  const Camera start = scene.camera;
  const vec3 forward = glm::normalize(start.look_at - start.position);
  Camera back = start;  // backed out of the box: the sky shows around it
  back.position -= 1.5f * scene.bounds.diagonal() * forward;
  back.look_at = back.position + forward + vec3(0.3f, 0.1f, 0.0f);
  Camera turned = start;  // looking back the way it came: everything is behind it
  turned.look_at = start.position - forward;
  const std::pair<Camera, Camera> moves[] = {
      {moved_camera(start), start}, {back, start}, {start, back}, {start, turned}};
  int sky = 0, behind = 0;
  for (const auto& [now, before] : moves) {
    const CameraRays after = CameraRays::from(now, kSize, kSize);
    const CameraRays previous = CameraRays::from(before, kSize, kSize);
    GBuffer g = gbuffer_of(data.view(), *tracer, after);
    compute_motion(data.view(), after, previous, g);
    const ConstGBufferView view = std::as_const(g).view();
    for (size_t i = 0; i < g.size(); ++i) {
      const vec2 want = motion_pixel(data.view(), after, previous, view, i);
      sky += !g.hit(i);
      behind += want.x == kOffscreenMotion;
      if (want.x == kOffscreenMotion) {
        ASSERT_EQ(g.motion[i], want) << i;
        continue;
      }
      ASSERT_NEAR(g.motion[i].x, want.x, 1e-3f * (1.0f + std::fabs(want.x))) << i;
      ASSERT_NEAR(g.motion[i].y, want.y, 1e-3f * (1.0f + std::fabs(want.y))) << i;
    }
  }
  EXPECT_GT(sky, kSize * kSize / 4);  // every case above was met, and often
  EXPECT_GT(behind, kSize * kSize / 2);
}

// A mesh moved between two frames: its pixels move by the projection of the offset, and the
// rest of the frame, under a still camera, does not move at all.
TEST(Motion, MovedMeshCarriesItsOwnMotion) {
  Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  SceneData data = SceneData::from(scene);
  const CameraRays rays = CameraRays::from(scene.camera, kSize, kSize);
  const uint32_t centre = kSize / 2 * kSize + kSize / 2;
  uint32_t mover = 0;
  {
    const GBuffer g = gbuffer_of(data.view(), *tracer, rays);
    ASSERT_TRUE(g.hit(centre));
    mover = g.mesh[centre];
  }
  const vec3 offset(0.02f, 0.01f, 0.0f);
  const SceneChange change = move_mesh(scene, mover, offset);
  tracer->update(scene, change.moved_meshes);
  data.refresh(scene, change.moved_meshes);
  GBuffer g = gbuffer_of(data.view(), *tracer, rays);
  compute_motion(data.view(), rays, rays, g);
  int on_mover = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (!g.hit(i)) continue;
    if (g.mesh[i] != mover) {
      ASSERT_EQ(g.motion[i], vec2(0.0f)) << "pixel " << i;
      continue;
    }
    ++on_mover;
    const vec2 expected = rays.project(g.position[i]) - rays.project(g.position[i] - offset);
    ASSERT_NEAR(g.motion[i].x, expected.x, 1e-3f);
    ASSERT_NEAR(g.motion[i].y, expected.y, 1e-3f);
    ASSERT_GT(glm::length(g.motion[i]), 0.1f);
  }
  EXPECT_GT(on_mover, 0);
  // The next frame, with nothing moved, is still again.
  data.forget_motion();
  compute_motion(data.view(), rays, rays, g);
  for (vec2 m : g.motion) ASSERT_EQ(m, vec2(0.0f));
}

// Small accumulating frames of direct light, for the tests through the Renderer.
FrameSettings small_frames() {
  FrameSettings settings;
  settings.width = settings.height = 32;
  settings.light_samples = 1;
  settings.accumulate = true;
  return settings;
}

// Through the Renderer: a camera move gives motion, a following frame at rest none.
TEST(Motion, RendererFillsMotionFrameAfterFrame) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  const FrameSettings settings = small_frames();
  renderer.render(scene.camera, settings);
  const Camera moved = moved_camera(scene.camera);
  float largest = 0.0f;
  for (vec2 m : renderer.render(moved, settings).gbuffer.motion)
    largest = std::max(largest, glm::length(m));
  EXPECT_GT(largest, 0.5f);
  for (vec2 m : renderer.render(moved, settings).gbuffer.motion) ASSERT_EQ(m, vec2(0.0f));
}

// The viewer's resolution scaler changes the size in motion: motion is then measured in the new
// frame's pixels (zero for a still camera), and the denoiser's history carries over.
TEST(Motion, ResizedFramesKeepTheirHistory) {
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  FrameSettings settings = small_frames();
  settings.denoise = true;
  for (int k = 0; k < 3; ++k) renderer.render(scene.camera, settings);
  settings.width = settings.height = 16;
  const Frame& f = renderer.render(scene.camera, settings);
  for (vec2 m : f.gbuffer.motion) ASSERT_LT(glm::length(m), 1e-3f);
  // Three frames of history (lengths 0, 1, 2), reprojected: the fourth frame counts 3.
  const std::vector<float>& length = renderer.denoiser().history_length();
  ASSERT_EQ(length.size(), size_t(16 * 16));
  EXPECT_EQ(*std::max_element(length.begin(), length.end()), 3.0f);
}

}  // namespace
}  // namespace bounce
