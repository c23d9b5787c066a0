#include "bounce/metrics/temporal_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bounce/core/error.h"

namespace bounce {

void FlickerAccumulator::add(const Image& frame) {
  if (frames_ == 0) {
    width_ = frame.width();
    height_ = frame.height();
    mean_.assign(frame.pixel_count() * 3, 0.0);
    m2_.assign(frame.pixel_count() * 3, 0.0);
  } else if (frame.width() != width_ || frame.height() != height_) {
    fail("flicker: frame {} is {}x{}, the first frame was {}x{}", frames_, frame.width(),
         frame.height(), width_, height_);
  }
  ++frames_;
  const double inv_n = 1.0 / double(frames_);
  const vec3* pixels = frame.data();
  for (size_t i = 0; i < frame.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      // Welford: the new mean, then the squared deviations from the old and the new mean.
      const size_t k = 3 * i + size_t(c);
      const double x = double(pixels[i][c]);
      const double delta = x - mean_[k];
      mean_[k] += delta * inv_n;
      m2_[k] += delta * (x - mean_[k]);
    }
}

double FlickerAccumulator::mean_deviation() const {
  if (frames_ == 0) return std::numeric_limits<double>::quiet_NaN();
  if (m2_.empty()) return 0.0;
  double sum = 0.0;
  for (const double m2 : m2_) sum += std::sqrt(std::max(0.0, m2) / double(frames_));
  return sum / double(m2_.size());
}

double FlickerAccumulator::mean_value() const {
  if (frames_ == 0) return std::numeric_limits<double>::quiet_NaN();
  if (mean_.empty()) return 0.0;
  double sum = 0.0;
  for (const double m : mean_) sum += m;
  return sum / double(mean_.size());
}

double FlickerAccumulator::flicker() const {
  if (frames_ == 0) return std::numeric_limits<double>::quiet_NaN();
  const double deviation = mean_deviation(), mean = mean_value();
  if (mean == 0.0) return deviation == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return deviation / mean;
}

double flicker(std::span<const Image> frames) {
  FlickerAccumulator acc;
  for (const Image& f : frames) acc.add(f);
  return acc.flicker();
}

BlockSums block_sums(const Image& image, int block) {
  if (block < 1) fail("block size {} is not positive", block);
  BlockSums b;
  b.width = image.width();
  b.height = image.height();
  b.block = block;
  b.blocks_x = (b.width + block - 1) / block;
  b.blocks_y = (b.height + block - 1) / block;
  b.sums.assign(size_t(b.blocks_x) * size_t(b.blocks_y) * 3, 0.0);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      const size_t k = (size_t(y / block) * size_t(b.blocks_x) + size_t(x / block)) * 3;
      const vec3 v = image.at(x, y);
      for (int c = 0; c < 3; ++c) b.sums[k + size_t(c)] += double(v[c]);
    }
  return b;
}

double block_error(const BlockSums& frame, const BlockSums& target) {
  if (frame.width != target.width || frame.height != target.height || frame.block != target.block)
    fail("settle: a {}x{} frame in {}-pixel blocks against a {}x{} target in {}-pixel blocks",
         frame.width, frame.height, frame.block, target.width, target.height, target.block);
  double difference = 0.0, total = 0.0;
  for (size_t k = 0; k < target.sums.size(); ++k) {
    difference += std::abs(frame.sums[k] - target.sums[k]);
    total += target.sums[k];
  }
  if (total == 0.0) return difference == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return difference / total;
}

int settle_frame(std::span<const double> errors, double tolerance) {
  int k = int(errors.size());
  while (k > 0 && errors[size_t(k) - 1] <= tolerance) --k;  // NaN compares false: beyond
  return k == int(errors.size()) ? kNotSettled : k;
}

std::vector<double> block_errors(std::span<const Image> frames, const Image& target, int block) {
  const BlockSums t = block_sums(target, block);
  std::vector<double> errors;
  errors.reserve(frames.size());
  for (const Image& f : frames) errors.push_back(block_error(block_sums(f, block), t));
  return errors;
}

int settle_frame(std::span<const Image> frames, const Image& target, double tolerance, int block) {
  return settle_frame(block_errors(frames, target, block), tolerance);
}

}  // namespace bounce
