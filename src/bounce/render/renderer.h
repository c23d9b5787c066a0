// The frame pipeline: scene update -> G-buffer (primary rays) -> direct light (shadow rays) ->
// technique.indirect -> composite -> tone map. Every stage is timed under its own name.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/timer.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/technique.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct FrameSettings {
  int width = 512;
  int height = 512;
  int light_samples = 16;    // stratified samples per area light per pixel per frame
  float exposure_ev = 0.0f;  // tone-map exposure in stops
  bool jitter = false;       // sub-pixel jitter of primary rays (for accumulation)
  // At rest (same camera, size and scene as the last frame) average direct light over frames;
  // with jitter this also antialiases. Techniques accumulate their own indirect light.
  bool accumulate = false;
  uint32_t seed = 0;  // decorrelates sample patterns between runs
};

struct Frame {
  GBuffer gbuffer;
  Image direct;              // direct light plus emitters seen directly (averaged at rest)
  int direct_frames = 1;     // frames averaged into `direct`
  Image indirect;            // the technique's indirect radiance
  Image color;               // linear composite
  std::vector<uint8_t> ldr;  // tone-mapped sRGB, 3 bytes per pixel
  StageTimes times;
  uint64_t primary_rays = 0;
  uint64_t shadow_rays = 0;
  TechniqueCounters technique;  // photons and rays of the indirect stage
};

class Renderer {
 public:
  Renderer(const Scene& scene, Tracer& tracer, std::unique_ptr<Technique> technique);
  Technique& technique() { return *technique_; }
  // Swaps the technique (a viewer's technique switch); it starts from the current scene.
  void set_technique(std::unique_ptr<Technique> technique);
  // Says the scene was edited or animated since the last frame: the next frame refits the
  // tracer for moved meshes, restarts the technique's accumulated state and direct averaging.
  void scene_changed(const SceneChange& change);
  // Poses `scene`, which must be the scene this renderer draws, at animation time t (seconds)
  // and passes the change on; the next frame's "scene" stage includes this work and the refit.
  void animate(Scene& scene, float t);
  // Renders the next frame from `camera`; the returned frame stays valid until the next call.
  const Frame& render(const Camera& camera, const FrameSettings& settings);
  uint32_t frame_index() const { return frame_index_; }

 private:
  void update_scene();
  void average_direct(const CameraRays& rays, const FrameSettings& settings);

  const Scene& scene_;
  Tracer& tracer_;
  std::unique_ptr<Technique> technique_;
  Frame frame_;
  uint32_t frame_index_ = 0;
  SceneChange pending_;
  double pose_ms_ = 0.0;  // animate() time since the last frame
  // Direct-light averaging at rest.
  Image direct_sum_;
  int direct_frames_ = 0;
  CameraRays last_rays_{};
  int last_light_samples_ = 0;
};

}  // namespace bounce
