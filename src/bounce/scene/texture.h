// An RGB texture in linear colour, sampled bilinearly with repeat wrapping.
#pragma once

#include <string>
#include <vector>

#include "bounce/core/math.h"

namespace bounce {

// Texture coordinates follow glTF: (0, 0) is the top-left texel of the image.
struct Texture {
  std::string name;  // usually the file it came from
  int width = 0;
  int height = 0;
  std::vector<vec3> texels;  // row-major from the top row, linear RGB

  vec3 sample(vec2 uv) const;
};

}  // namespace bounce
