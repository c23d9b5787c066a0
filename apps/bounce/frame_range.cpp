#include "frame_range.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/error.h"

namespace bounce::app {

FrameRange make_frame_range(double from, double to, double fps, int every, int64_t warmup) {
  if (!std::isfinite(fps) || fps <= 0.0 || fps > kMaxSequenceFps)
    fail("--fps must be in (0, {:g}] frames per second, got {}", kMaxSequenceFps, fps);
  if (every < 1) fail("--every must be at least 1, got {}", every);
  if (warmup < 0 || warmup > kMaxSequenceFrames)
    fail("--warmup must be in [0, {}] frames, got {}", kMaxSequenceFrames, warmup);
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
  const double start = from * fps;  // frames from 0 s to `from`
  if (std::fabs(start - std::round(start)) <= kTolerance) r.origin = int64_t(std::round(start));
  r.warmup = std::min(warmup, r.origin >= 0 ? r.origin : int64_t(std::floor(start)));
  return r;
}

}  // namespace bounce::app
