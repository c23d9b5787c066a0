// Temporal metrics over sequences of linear images: flicker on a static scene (DESIGN.md
// "Metrics", temporal stability) and the settle time of indirect light after a change.
// Plain functions over images; src/bounce/eval/temporal_runs.h renders the sequences.
#pragma once

#include <span>
#include <vector>

#include "bounce/core/image.h"

namespace bounce {

// Flicker, fed frame by frame: with v(p, c, t) the linear value of pixel p, channel c (R, G, B)
// in frame t,
//   flicker = mean over p and c of std_t v(p, c, t)  /  mean over p, c and t of v(p, c, t)
// where std_t is the POPULATION standard deviation over the frames (divide by the frame count,
// not count - 1). Per channel, then averaged over the 3 channels (as MSE is), not luminance.
// Running mean and variance per pixel-channel by Welford's update, in double precision.
// Frames alternating between two constant images a and b (an even count) give
// (|a - b| / 2) / ((a + b) / 2); identical frames give 0.
class FlickerAccumulator {
 public:
  // Adds a frame; every frame must have the first one's size (throws Error otherwise).
  void add(const Image& frame);
  int frames() const { return frames_; }
  // Mean over pixels and channels of the per-pixel-channel population standard deviation.
  double mean_deviation() const;
  // Mean over pixels, channels and frames.
  double mean_value() const;
  // mean_deviation() / mean_value(); 0 when both are 0 (all frames black), +inf when only the
  // mean is 0, NaN before the first frame.
  double flicker() const;

 private:
  int width_ = 0, height_ = 0;
  int frames_ = 0;
  std::vector<double> mean_;  // per pixel-channel running mean
  std::vector<double> m2_;    // per pixel-channel running sum of squared deviations
};

// Flicker of a whole sequence (FlickerAccumulator over `frames`).
double flicker(std::span<const Image> frames);

// Settle time. The error of a frame against a target image is the relative L1 distance of
// their block sums: the image is cut into block x block pixel squares (partial squares at the
// right and bottom edges count with the pixels they hold), each block's R, G and B values are
// summed, and
//   error = sum over blocks and channels |frame sum - target sum|
//           / sum over blocks and channels target sum.
// For full blocks this is sum |block mean - target block mean| / sum target block mean; block
// averages make it robust against per-pixel noise, so it measures the lag of the estimate, not
// the noise of single pixels. The settle frame of a sequence of errors e_0, e_1, ... (frame 0 is
// the first frame rendered after the change) is the first k with e_j <= tolerance for every
// j >= k in the sequence; 0 means the first frame after the change is already within tolerance.
inline constexpr int kSettleBlock = 16;           // block side, pixels
inline constexpr double kSettleTolerance = 0.05;  // 5%
inline constexpr int kNotSettled = -1;            // the last frame is still beyond tolerance

struct BlockSums {
  int width = 0, height = 0;  // image size in pixels
  int block = 0;              // block side in pixels
  int blocks_x = 0, blocks_y = 0;
  std::vector<double> sums;  // 3 per block (R, G, B), row-major over blocks
};

// Block sums of an image (throws Error when block < 1).
BlockSums block_sums(const Image& image, int block = kSettleBlock);
// Relative L1 distance of `frame` to `target` (same image size and block, else Error).
// 0 when both are all zero; +inf when only the target is.
double block_error(const BlockSums& frame, const BlockSums& target);
// The first index from which every error is <= tolerance; kNotSettled when the sequence is
// empty or its last error exceeds the tolerance (NaN counts as beyond it).
int settle_frame(std::span<const double> errors, double tolerance = kSettleTolerance);
// The errors of `frames` against `target`, and their settle frame.
std::vector<double> block_errors(std::span<const Image> frames, const Image& target,
                                 int block = kSettleBlock);
int settle_frame(std::span<const Image> frames, const Image& target,
                 double tolerance = kSettleTolerance, int block = kSettleBlock);

}  // namespace bounce
