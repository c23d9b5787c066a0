#include "frame_range.h"

#include <cmath>

#include "bounce/core/error.h"

namespace bounce::app {

FrameRange make_frame_range(double from, double to, double fps, int every) {
  if (!std::isfinite(fps) || fps <= 0.0 || fps > kMaxSequenceFps)
    fail("--fps must be in (0, {:g}] frames per second, got {}", kMaxSequenceFps, fps);
  if (every < 1) fail("--every must be at least 1, got {}", every);
  if (!std::isfinite(from) || from < 0.0)
    fail("--from must be a finite time of at least 0 s, got {}", from);
  if (!std::isfinite(to)) fail("--to must be a finite time, got {}", to);
  if (to < from) fail("--to {:g} s is before --from {:g} s", to, from);
  constexpr double kTolerance = 1e-6;  // frames
  const double intervals = (to - from) * fps;
  if (!(intervals + kTolerance < double(kMaxSequenceFrames)))
    fail(
        "--from {:g} --to {:g} at --fps {:g} is {:.0f} frames; at most {} per run (split the "
        "range)",
        from, to, fps, std::floor(intervals + kTolerance) + 1.0, kMaxSequenceFrames);
  FrameRange r;
  r.from = from;
  r.to = to;
  r.fps = fps;
  r.every = every;
  r.count = int64_t(std::floor(intervals + kTolerance)) + 1;
  return r;
}

}  // namespace bounce::app
