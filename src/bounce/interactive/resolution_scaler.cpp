#include "bounce/interactive/resolution_scaler.h"

#include <algorithm>
#include <cmath>

namespace bounce {

float ResolutionScaler::update(double frame_ms, bool moving) {
  const ResolutionScalerSettings& s = settings_;
  if (s.target_ms <= 0.0 || !moving) {
    ideal_ = scale_ = s.max_scale;
    return scale_;
  }
  if (!(frame_ms > 0.0)) return scale_;
  // Pixels scale with scale^2 and so, to first order, does the frame time.
  const float wanted = scale_ * float(std::sqrt(s.target_ms / frame_ms));
  // Halfway towards the estimate each frame: fast enough to follow, damped against noise.
  ideal_ = std::clamp(0.5f * (ideal_ + wanted), s.min_scale, s.max_scale);
  scale_ = std::clamp(std::floor(ideal_ / s.step) * s.step, s.min_scale, s.max_scale);
  return scale_;
}

}  // namespace bounce
