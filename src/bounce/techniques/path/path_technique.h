// Technique "path": the unbiased path tracer in the frame pipeline. It writes the indirect term
// only (light that bounced at least once after the G-buffer point; the direct stage supplies the
// rest) and, with accumulation on, averages it over frames while nothing changes.
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
  IndirectHistory indirect_history() const override { return IndirectHistory::kAccumulated; }
  // Builds the light picker when lights or geometry changed.
  void prepare(const PrepareContext& context) override;
  void indirect(const FrameContext& context, Image& out) override;
  // Frames averaged into the current estimate (0 right after a restart).
  int accumulated_frames() const { return frames_; }

 private:
  int max_bounces_ = -1;
  int rr_start_ = 3;
  int light_candidates_ = PathSettings().light_candidates;
  int samples_ = 1;
  int seed_ = 0;

  LightPicker lights_;
  std::vector<vec3> sums_;  // per pixel, over the frames since the last restart
  int frames_ = 0;
};

}  // namespace bounce
