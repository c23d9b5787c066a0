// A linear-RGB float image plus the arithmetic the tools and metrics need.
#pragma once

#include <vector>

#include "bounce/core/image_view.h"
#include "bounce/core/math.h"

namespace bounce {

class Image {
 public:
  Image() = default;
  Image(int width, int height, vec3 fill = vec3(0.0f));

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return pixels_.size(); }
  bool empty() const { return pixels_.empty(); }

  vec3& at(int x, int y) { return pixels_[size_t(y) * width_ + x]; }
  const vec3& at(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }
  vec3* data() { return pixels_.data(); }
  const vec3* data() const { return pixels_.data(); }
  std::vector<vec3>& pixels() { return pixels_; }
  ImageView view() { return {pixels_.data(), width_, height_}; }
  ConstImageView view() const { return {pixels_.data(), width_, height_}; }
  const std::vector<vec3>& pixels() const { return pixels_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<vec3> pixels_;
};

// Element-wise arithmetic; the binary forms require equal sizes (throw Error otherwise).
Image operator+(const Image& a, const Image& b);
Image operator-(const Image& a, const Image& b);
Image operator*(const Image& a, const Image& b);
Image operator*(const Image& a, float s);
Image& operator+=(Image& a, const Image& b);
Image& operator*=(Image& a, float s);
Image abs_diff(const Image& a, const Image& b);
// Mean colour over a rectangle [x0, x1) x [y0, y1) (the whole image by default).
vec3 mean(const Image& image);
vec3 mean(const Image& image, int x0, int y0, int x1, int y1);
// Per-pixel luminance (Rec. 709 / sRGB primaries), row-major.
std::vector<float> luminance(const Image& image);

}  // namespace bounce
