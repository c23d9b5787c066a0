// Quality at rest, speed in motion: picks the internal resolution scale of the next frame. While
// the camera or the scene moves, the scale follows the measured frame time towards a target
// (frame time grows with the pixel count, the square of the scale); at rest it returns to full
// resolution so that accumulation converges to a sharp image.
#pragma once

namespace bounce {

struct ResolutionScalerSettings {
  double target_ms = 33.0;  // frame-time goal in motion; 0 turns scaling off (always max_scale)
  float min_scale = 0.25f;
  float max_scale = 1.0f;
  float step = 1.0f / 16.0f;  // scales are multiples of this, so sizes do not change every frame
};

class ResolutionScaler {
 public:
  explicit ResolutionScaler(ResolutionScalerSettings settings = {}) : settings_(settings) {}
  ResolutionScalerSettings& settings() { return settings_; }
  float scale() const { return scale_; }
  // Feeds the time of the frame just rendered at scale(); `moving` says whether the next frame
  // follows a change (camera, scene or settings). Returns the scale for the next frame.
  float update(double frame_ms, bool moving);

 private:
  ResolutionScalerSettings settings_;
  float scale_ = 1.0f;
  float ideal_ = 1.0f;  // unquantised, smoothed scale in motion
};

}  // namespace bounce
