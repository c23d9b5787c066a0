// The frames of a sequence (bounce sequence): frame k is at time from + k / fps, for k = 0 up to
// and including (to - from) * fps; every Nth frame is kept (written), but all are rendered, since
// each frame builds on the temporal state of the one before. Warm-up frames (k = -warmup .. -1)
// are rendered before `from` and never written: they rebuild that state when a range of a
// longer sequence runs on its own (on another machine).
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
  int64_t count = 1;   // frames from `from` on (rendered and kept every `every`)
  int64_t warmup = 0;  // frames rendered before `from`, not written
  // from * fps when `from` falls on the frame grid of a sequence starting at 0 s (within 1e-6 of
  // a frame), else -1. On the grid, frame k is frame origin + k of that sequence, at the very
  // same time, so ranges rendered apart line up with one run.
  int64_t origin = -1;

  double time(int64_t k) const {
    return origin >= 0 ? double(origin + k) / fps : from + double(k) / fps;
  }
  // The frame's number in the sequence from 0 s (origin + k), or k when off the grid.
  int64_t number(int64_t k) const { return origin >= 0 ? origin + k : k; }
  bool kept(int64_t k) const { return k % every == 0; }
  int64_t kept_count() const { return (count + every - 1) / every; }
};

// Checks the values (throws Error naming the option and the problem: a non-finite or negative
// time, to before from, fps outside (0, kMaxSequenceFps], every below 1, more than
// kMaxSequenceFrames frames) and counts the frames. (to - from) * fps within 1e-6 of an integer
// counts as that integer, so decimal times that binary floating point misses by a rounding error
// (0.3 - 0.1 = 0.19999999999999998) give the frame a user expects at `to`. `warmup` (>= 0) is
// cut to the frames that exist between 0 s and `from`, as a run from 0 s has no earlier ones.
FrameRange make_frame_range(double from, double to, double fps, int every, int64_t warmup = 0);

}  // namespace bounce::app
