#include "bounce/scene/environment_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/core/image_io.h"

namespace bounce {

namespace {

// Cumulative sums of `weights` normalised to end at exactly 1 (doubles, so long rows keep
// their small entries). All-zero weights give a uniform table; the caller never picks such a
// row, but a table must still be valid.
void cumulate(const double* weights, size_t n, float* cdf) {
  double total = 0.0;
  for (size_t i = 0; i < n; ++i) total += weights[i];
  double running = 0.0;
  for (size_t i = 0; i < n; ++i) {
    running += total > 0.0 ? weights[i] : 1.0;
    cdf[i] = float(running / (total > 0.0 ? total : double(n)));
  }
  // From the last entry with weight on, exactly 1: u < 1 never lands on a weightless entry.
  size_t last = n - 1;
  while (total > 0.0 && last > 0 && weights[last] <= 0.0) --last;
  for (size_t i = last; i < n; ++i) cdf[i] = 1.0f;
}

}  // namespace

EnvironmentMap EnvironmentMap::from_image(const Image& image, const std::string& name) {
  if (image.empty()) fail("{}: the environment map is empty", name);
  EnvironmentMap m;
  m.name_ = name;
  m.width_ = image.width();
  m.height_ = image.height();
  m.texels_ = image.pixels();
  const size_t w = size_t(m.width_), h = size_t(m.height_);
  for (size_t y = 0; y < h; ++y)
    for (size_t x = 0; x < w; ++x) {
      const vec3 c = m.texels_[y * w + x];
      if (!is_finite(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
        fail("{}: environment map texel ({}, {}) is negative or not finite ({}, {}, {})", name, x,
             y, c.x, c.y, c.z);
      m.max_value_ = std::max(m.max_value_, max_component(c));
    }

  // Weights: luminance times sin(theta) at the row centre, the texel's share of solid angle.
  std::vector<double> weights(w), row_weights(h);
  m.conditional_cdf_.resize(w * h);
  m.marginal_cdf_.resize(h);
  glm::dvec3 integral(0.0);  // of the radiance over the sphere
  for (size_t y = 0; y < h; ++y) {
    const double theta0 = kPi * double(y) / double(h), theta1 = kPi * double(y + 1) / double(h);
    const double sin_centre = std::sin(0.5 * (theta0 + theta1));
    const double solid_angle = (std::cos(theta0) - std::cos(theta1)) * 2.0 * kPi / double(w);
    double row = 0.0;
    for (size_t x = 0; x < w; ++x) {
      const vec3 c = m.texels_[y * w + x];
      weights[x] = double(luminance(c)) * sin_centre;
      if (!(weights[x] > 0.0)) weights[x] = 0.0;
      row += weights[x];
      integral += glm::dvec3(c) * solid_angle;
    }
    cumulate(weights.data(), w, m.conditional_cdf_.data() + y * w);
    row_weights[y] = row;
  }
  // A black map: sample by solid angle alone (it sends no light, but tables must be valid).
  double total = 0.0;
  for (double r : row_weights) total += r;
  if (!(total > 0.0))
    for (size_t y = 0; y < h; ++y) row_weights[y] = std::sin(kPi * (double(y) + 0.5) / double(h));
  cumulate(row_weights.data(), h, m.marginal_cdf_.data());
  m.mean_ = vec3(integral / (4.0 * kPi));
  return m;
}

EnvironmentMap EnvironmentMap::load(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr" && ext != ".hdr")
    fail("{}: an environment map must be an .exr or .hdr file (linear HDR), not '{}'", path, ext);
  return from_image(load_image(path), path);
}

}  // namespace bounce
