// A 2 x 2 texture of red, green, blue and yellow texels (top row first): lookups that read the
// texels and lookups that read their mean tell apart.
#pragma once

#include "bounce/scene/texture.h"

namespace bounce {

inline Texture checker_texture() {
  Texture t;
  t.name = "checker";
  t.width = 2;
  t.height = 2;
  t.texels = {vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f),
              vec3(1.0f, 1.0f, 0.0f)};
  return t;
}

}  // namespace bounce
