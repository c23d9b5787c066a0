#include "bounce/scene/texture.h"

namespace bounce {

vec3 mean_texel(const Texture& t) {
  glm::dvec3 sum(0.0);
  for (const vec3& v : t.texels) sum += glm::dvec3(v);
  return t.texels.empty() ? vec3(0.0f) : vec3(sum / double(t.texels.size()));
}

}  // namespace bounce
