// What the viewer shows and edits, without a window: the scene, its tracer and the frame
// pipeline, the fly camera, the flashlight, the animation clock and the resolution scaler. The
// window (view_window.cpp) feeds it input and script actions and displays its frames.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "../options.h"
#include "bounce/interactive/flashlight.h"
#include "bounce/interactive/fly_camera.h"
#include "bounce/interactive/resolution_scaler.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/tracer.h"
#include "script.h"

namespace bounce::app {

struct ViewOptions {
  FrameOptions frame;      // width and height are the window's
  int frames = 0;          // stop after this many frames (0: run until closed or the script ends)
  std::string screenshot;  // saved after the last frame
  std::string script;
  bool hide_ui = false;
  double target_ms = 33.0;  // frame-time goal in motion (0: always full resolution)
};

class ViewSession {
 public:
  explicit ViewSession(const ViewOptions& options);

  // Advances the clock by dt seconds and renders one frame for an output of out_w x out_h.
  const Frame& render(int out_w, int out_h, double dt);
  const Frame& frame() const { return *frame_; }
  bool has_frame() const { return frame_ != nullptr; }

  // Controls (the panel, the keyboard and scripts use these).
  FlyCamera& camera() { return camera_; }
  void reset_camera();
  bool flashlight() const { return flashlight_index_.has_value(); }
  void set_flashlight(bool on);
  FlashlightSettings& flashlight_settings() { return flashlight_settings_; }
  void flashlight_edited() { lights_changed(); }
  const std::string& technique_name() const { return technique_name_; }
  void set_technique(const std::string& name);
  Technique& technique() { return renderer_->technique(); }
  void set_param(const std::string& name, const std::string& value);
  Scene& scene() { return scene_; }
  // After editing scene.lights or an emissive material.
  void lights_changed();
  void materials_changed();
  // Moves area light `index` by `offset` (the panel's area-light position).
  void move_area_light(size_t index, vec3 offset);
  // Moves mesh `index` by `offset` (the panel's object list).
  void move_mesh(uint32_t index, vec3 offset);
  float& exposure() { return exposure_; }
  // --shadow-rays: auto, all or one (FrameOptions::shadow_rays), from the panel too.
  std::string& shadow_rays() { return options_.frame.shadow_rays; }
  // --moving-lights-in-history (FrameOptions), from the panel too.
  bool& moving_lights_in_history() { return options_.frame.moving_lights_in_history; }
  // Temporal reuse and denoising, its parameters, and what the window shows (debug views).
  bool& denoise() { return denoise_; }
  Denoiser& denoiser() { return renderer_->denoiser(); }
  DenoiseView& view() { return view_; }
  bool& playing() { return playing_; }
  bool& follow_path() { return follow_path_; }
  float time() const { return time_; }
  void set_time(float t);
  ResolutionScaler& scaler() { return scaler_; }
  // A fixed internal resolution scale (scripts); nullopt hands it back to the scaler.
  std::optional<float>& fixed_scale() { return fixed_scale_; }
  bool moving() const { return moving_; }
  const std::deque<float>& frame_ms_history() const { return history_; }
  uint64_t frames_rendered() const { return frames_; }

  // Runs one script action that concerns the scene or camera; returns false for the verbs the
  // window handles itself (wait, ui, screenshot, quit).
  bool apply(const ScriptAction& action);

 private:
  void place_flashlight();

  ViewOptions options_;
  Scene scene_;
  std::unique_ptr<Tracer> tracer_;
  std::unique_ptr<Renderer> renderer_;
  std::string technique_name_;
  const Frame* frame_ = nullptr;

  FlyCamera camera_;
  std::optional<size_t> flashlight_index_;
  FlashlightSettings flashlight_settings_;
  SceneChange pending_;

  float exposure_ = 0.0f;
  bool denoise_ = true;
  DenoiseView view_ = DenoiseView::kDenoised;
  bool playing_ = false;
  bool follow_path_ = false;
  float time_ = 0.0f;
  bool time_set_ = true;  // pose the scene at time_ on the next frame

  ResolutionScaler scaler_;
  std::optional<float> fixed_scale_;
  bool moving_ = true;
  double last_frame_ms_ = 0.0;
  std::deque<float> history_;
  uint64_t frames_ = 0;
};

}  // namespace bounce::app
