// The frames of a sequence (bounce sequence): frame k is at time from + k / fps, for k = 0 up to
// and including (to - from) * fps; every Nth frame is kept (written), but all are rendered, since
// each frame builds on the temporal state of the one before.
#pragma once

#include <cstdint>

namespace bounce::app {

constexpr int64_t kMaxSequenceFrames = 100000;  // per run; longer runs split the range
constexpr double kMaxSequenceFps = 1000.0;

struct FrameRange {
  double from = 0.0;  // seconds
  double to = 0.0;    // seconds, >= from
  double fps = 30.0;
  int every = 1;
  int64_t count = 1;  // frames rendered

  double time(int64_t k) const { return from + double(k) / fps; }
  bool kept(int64_t k) const { return k % every == 0; }
  int64_t kept_count() const { return (count + every - 1) / every; }
};

// Checks the values (throws Error naming the option and the problem: a non-finite or negative
// time, to before from, fps outside (0, kMaxSequenceFps], every below 1, more than
// kMaxSequenceFrames frames) and counts the frames. (to - from) * fps within 1e-6 of an integer
// counts as that integer, so decimal times that binary floating point misses by a rounding error
// (0.3 - 0.1 = 0.19999999999999998) give the frame a user expects at `to`.
FrameRange make_frame_range(double from, double to, double fps, int every);

}  // namespace bounce::app
