// EnvironmentMap: an equirectangular HDR map (.exr or .hdr) with the tables that sample it by
// luminance (scene/environment.h describes the layout and the distribution). Immutable once
// built, so scenes and their flattened copies share one by pointer.
#pragma once

#include <string>
#include <vector>

#include "bounce/core/image.h"
#include "bounce/core/math.h"
#include "bounce/scene/environment.h"

namespace bounce {

class EnvironmentMap {
 public:
  // The map of `image` (linear RGB); `name` goes in messages. Throws Error naming `name` for an
  // empty image or a texel that is negative or not finite.
  static EnvironmentMap from_image(const Image& image, const std::string& name);
  // Loads a .exr or .hdr file (core/image_io.h); errors name the file.
  static EnvironmentMap load(const std::string& path);

  const std::string& name() const { return name_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // The map's radiance averaged over the sphere (by solid angle): what LightRecord::map_mean
  // holds, so that the light's power counts the map.
  vec3 mean() const { return mean_; }
  // The largest texel value, for the scene's emission limit.
  float max_value() const { return max_value_; }

  // Valid while this object lives.
  EnvironmentMapView view() const {
    return {texels_.data(), marginal_cdf_.data(), conditional_cdf_.data(), width_, height_};
  }

 private:
  std::string name_;
  int width_ = 0, height_ = 0;
  std::vector<vec3> texels_;
  std::vector<float> marginal_cdf_, conditional_cdf_;
  vec3 mean_{0.0f};
  float max_value_ = 0.0f;
};

}  // namespace bounce
