#include "bounce/core/image.h"

#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/error.h"

namespace bounce {

namespace {

void require_same_size(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height()) {
    fail("image sizes differ: {}x{} vs {}x{}", a.width(), a.height(), b.width(), b.height());
  }
}

// Applies op to each pair of pixels of two equally sized images.
template <typename Op>
Image combine(const Image& a, const Image& b, Op op) {
  require_same_size(a, b);
  Image result(a.width(), a.height());
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    result.pixels()[i] = op(a.pixels()[i], b.pixels()[i]);
  }
  return result;
}

}  // namespace

Image::Image(int width, int height, vec3 fill) {
  if (width < 0 || height < 0) fail("image size must not be negative: {}x{}", width, height);
  width_ = width;
  height_ = height;
  pixels_.assign(size_t(width) * size_t(height), fill);
}

Image operator+(const Image& a, const Image& b) {
  return combine(a, b, [](vec3 p, vec3 q) { return p + q; });
}

Image operator-(const Image& a, const Image& b) {
  return combine(a, b, [](vec3 p, vec3 q) { return p - q; });
}

Image operator*(const Image& a, const Image& b) {
  return combine(a, b, [](vec3 p, vec3 q) { return p * q; });
}

Image operator*(const Image& a, float s) {
  Image result = a;
  result *= s;
  return result;
}

Image& operator+=(Image& a, const Image& b) {
  require_same_size(a, b);
  for (size_t i = 0; i < a.pixel_count(); ++i) a.pixels()[i] += b.pixels()[i];
  return a;
}

Image& operator*=(Image& a, float s) {
  for (vec3& p : a.pixels()) p *= s;
  return a;
}

Image abs_diff(const Image& a, const Image& b) {
  return combine(a, b, [](vec3 p, vec3 q) { return glm::abs(p - q); });
}

vec3 mean(const Image& image) {
  return mean(image, 0, 0, image.width(), image.height());
}

vec3 mean(const Image& image, int x0, int y0, int x1, int y1) {
  if (x0 < 0 || y0 < 0 || x1 > image.width() || y1 > image.height() || x0 >= x1 || y0 >= y1) {
    fail("mean: rectangle [{}, {}) x [{}, {}) is empty or outside the {}x{} image", x0, x1, y0, y1,
         image.width(), image.height());
  }
  // Sum in double: a float sum over millions of pixels loses several digits.
  glm::dvec3 sum(0.0);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) sum += glm::dvec3(image.at(x, y));
  }
  const double count = double(x1 - x0) * double(y1 - y0);
  return vec3(sum / count);
}

std::vector<float> luminance(const Image& image) {
  std::vector<float> result(image.pixel_count());
  for (size_t i = 0; i < result.size(); ++i) result[i] = luminance(image.pixels()[i]);
  return result;
}

}  // namespace bounce
