// The frame pipeline: scene update -> technique.prepare -> G-buffer (primary rays, motion) ->
// direct light (shadow rays) -> technique.indirect -> denoise (temporal reuse and filtering,
// denoiser.h) -> composite -> tone map. Every stage is timed under its
// own name. The Renderer owns the one notion of what changed since the last frame (SceneChange)
// and, at rest with accumulation on, the averaging of frames into a converged image.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/timer.h"
#include "bounce/render/denoiser.h"
#include "bounce/render/device_pipeline.h"
#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer.h"
#include "bounce/render/light_change_region.h"
#include "bounce/render/light_picker.h"
#include "bounce/render/primary_raster.h"
#include "bounce/render/technique.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_change.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"

namespace bounce {

struct FrameSettings {
  int width = 512;
  int height = 512;
  int light_samples = 16;    // stratified samples per area light per pixel per frame
  float exposure_ev = 0.0f;  // tone-map exposure in stops
  bool jitter = false;       // sub-pixel jitter of primary rays (for accumulation)
  // Accumulation at rest: while nothing changes (SceneChange::any() false), frames average into
  // a converged image: direct light and per-frame indirect light by the Renderer, accumulating
  // techniques (IndirectHistory::kAccumulated) by themselves. With jitter this also antialiases.
  // Off, every frame is what a moving camera would show.
  bool accumulate = false;
  // Temporal reuse and denoising (denoiser.h; its parameters are Renderer::denoiser().params()):
  // with accumulation, history follows surfaces through camera and object motion and frames at
  // rest converge; without, every frame is filtered on its own.
  bool denoise = false;
  DenoiseView view = DenoiseView::kDenoised;  // what `color` shows (debug views keep history)
  uint32_t seed = 0;                          // decorrelates sample patterns between runs
  // One shadow ray per pixel for all its light samples, chosen by their unshadowed contribution
  // (direct_light_pixel): the real-time setting for scenes with several lights.
  bool one_shadow_ray = false;
  // Whether Frame::color (linear) must reach the host. The CPU has it anyway; a GPU frame copies
  // it back only when asked (bench and the viewer show `ldr`, a quarter of the bytes).
  bool host_color = true;
  // Primary visibility by rasterisation (primary_raster.h) rather than a traced ray per pixel,
  // where it pays (raster_pays: enough pixels per triangle): the same surfaces, found faster.
  // Off for comparison.
  bool raster_primary = true;
  // With the denoiser's history, punctual lights that moved this frame (a carried flashlight)
  // are shaded apart, each with its own shadow ray, and added after the denoiser: their light is
  // exact in every frame instead of lagging in a history (DirectSettings::apart). Off for
  // comparison.
  bool moving_lights_apart = true;

  bool operator==(const FrameSettings&) const = default;
};

// The direct stage's settings for frame `frame` of a run with these frame settings (both
// backends take them from here).
inline DirectSettings direct_settings(const FrameSettings& settings, uint32_t frame) {
  DirectSettings d{settings.light_samples, frame, settings.seed};
  d.one_shadow_ray = settings.one_shadow_ray;
  return d;
}

struct Frame {
  GBuffer gbuffer;
  Image direct;    // direct light plus emitters seen directly (averaged at rest, or denoised)
  Image indirect;  // the technique's indirect radiance (averaged at rest, or denoised)
  // The light of the lights set apart (DirectSettings::apart), added to `direct` after the
  // denoiser; its size is kept between frames, its pixels are this frame's only when any is.
  Image apart;
  Image color;  // linear composite (empty from a GPU frame unless FrameSettings::host_color)
  std::vector<uint8_t> ldr;   // tone-mapped sRGB, 3 bytes per pixel
  int width = 0, height = 0;  // the frame's size (ldr's)
  int frames_averaged = 1;    // frames that went into this one at rest (1 after any change)
  SceneChange change;         // what changed since the previous frame
  StageTimes times;
  uint64_t primary_rays = 0;
  uint64_t shadow_rays = 0;
  TechniqueCounters technique;  // photons and rays of the prepare and indirect stages
};

class Renderer {
 public:
  Renderer(const Scene& scene, Tracer& tracer, std::unique_ptr<Technique> technique);
  // Runs the frame's stages on another device from now on (null: back to the CPU). The scene
  // update and the decisions about history stay here, so both backends see the same frames.
  void set_device(std::unique_ptr<DevicePipeline> device);
  const DevicePipeline* device() const { return device_.get(); }
  Technique& technique() { return *technique_; }
  // Swaps the technique (a viewer's technique switch); it starts from the current scene.
  void set_technique(std::unique_ptr<Technique> technique);
  // Says the scene was edited or animated since the last frame: the next frame refits the
  // tracer for moved meshes and hands the change to the technique.
  void scene_changed(const SceneChange& change);
  // Poses `scene`, which must be the scene this renderer draws, at animation time t (seconds)
  // and passes the change on; the next frame's "scene" stage includes this work and the refit.
  void animate(Scene& scene, float t);
  // What the next render(camera, settings) would see as changed: scene edits reported so far,
  // the camera, the image size (unless ignore_size) and parameters. A viewer asks this to know
  // whether it is at rest before it chooses the frame's size.
  SceneChange next_change(const Camera& camera, const FrameSettings& settings,
                          bool ignore_size = false) const;
  // Renders the next frame from `camera`; the returned frame stays valid until the next call.
  const Frame& render(const Camera& camera, const FrameSettings& settings);
  uint32_t frame_index() const { return frame_index_; }
  // Numbers the next frame `index`: its jitter and sample seeds follow the frame number, so a
  // sequence started part way (bounce sequence --from, on another machine) draws the samples a
  // run from the start draws for the same frames.
  void set_frame_index(uint32_t index) { frame_index_ = index; }
  // The temporal reuse and denoising stage (FrameSettings::denoise) and its parameters.
  Denoiser& denoiser() { return denoiser_; }
  const Denoiser& denoiser() const { return denoiser_; }

 private:
  // A frame's parameters as text: the technique's and the frame settings that change images.
  std::vector<std::string> parameter_state(const FrameSettings& settings) const;
  // Pending scene edits plus what the camera, size and `parameters` (parameter_state) add.
  SceneChange change_since_last(const Camera& camera, const FrameSettings& settings,
                                const std::vector<std::string>& parameters, bool ignore_size) const;
  // How the denoiser's history relates to this frame (from the change and the settings).
  HistoryState history_state(const SceneChange& change, const FrameSettings& settings) const;
  // Averages `image` with the frames before it while at rest; restarts when `rest` is false.
  // Without accumulation nothing is kept.
  struct RunningAverage {
    Image sum;
    int frames = 0;
    void add(Image& image, bool accumulate, bool rest);
  };

  const Scene& scene_;
  Tracer& tracer_;
  SceneData scene_data_;      // the scene as the G-buffer and direct-light kernels read it
  LightPicker lights_;        // lights by power: direct light's candidates in many-light scenes
  LightsApart picker_apart_;  // the lights `lights_` leaves out (those last set apart)
  std::unique_ptr<Technique> technique_;
  Frame frame_;
  uint32_t frame_index_ = 0;
  SceneChange pending_ = SceneChange::all();  // scene edits since the last frame
  double pose_ms_ = 0.0;                      // animate() time since the last frame
  // What the last frame was rendered with, to tell what changed.
  Camera last_camera_{};
  CameraRays last_rays_{};  // the last frame's camera for its size: motion vectors start there
  int last_width_ = 0, last_height_ = 0;
  DenoiseSettings last_denoise_;
  std::vector<LightRecord> last_lights_;
  // The lights as the denoiser's history holds them: those set apart dark (history_lights).
  std::vector<LightRecord> last_history_lights_;
  int rest_frames_ = 0;  // frames since the last change (Frame::frames_averaged)
  std::vector<std::string> last_parameters_;
  RunningAverage direct_average_, indirect_average_;
  Denoiser denoiser_;
  PrimaryRaster raster_;  // this frame's primary visibility (FrameSettings::raster_primary)
  std::unique_ptr<DevicePipeline> device_;
};

}  // namespace bounce
