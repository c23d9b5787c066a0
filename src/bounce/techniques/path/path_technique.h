// Technique "path": the unbiased path tracer in the frame pipeline. It writes the indirect term
// only (light that bounced at least once after the G-buffer point; the direct stage supplies the
// rest) and averages it over frames while the scene, camera, size and parameters stay the same.
#pragma once

#include <vector>

#include "bounce/render/light_picker.h"
#include "bounce/render/technique.h"
#include "bounce/techniques/path/path_tracer.h"

namespace bounce {

class PathTracing final : public Technique {
 public:
  PathTracing();
  std::string name() const override { return "path"; }
  void scene_changed(const Scene& scene, const Tracer& tracer) override;
  void indirect(const FrameContext& context, Image& out) override;
  // Frames averaged into the current estimate (0 right after a restart).
  int accumulated_frames() const { return frames_; }

 private:
  // What the estimate depends on besides the scene: a change restarts the average.
  struct State {
    CameraRays camera;
    int width = 0, height = 0;
    int max_bounces = 0, rr_start = 0, samples = 0, seed = 0;
    bool operator==(const State&) const = default;
  };
  void restart();

  int max_bounces_ = -1;
  int rr_start_ = 3;
  int samples_ = 1;
  int seed_ = 0;
  bool accumulate_ = true;

  LightPicker lights_;
  bool prepared_ = false;
  State state_;
  std::vector<vec3> sums_;  // per pixel, over the frames since the last restart
  int frames_ = 0;
};

}  // namespace bounce
