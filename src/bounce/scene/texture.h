// An RGB texture in linear colour, sampled bilinearly with repeat wrapping.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

// An affine map of texture coordinates, uv' = (row_u . (u, v, 1), row_v . (u, v, 1)): glTF's
// KHR_texture_transform, offset * rotation * scale (the extension's matrix).
struct TextureTransform {
  vec3 row_u{1.0f, 0.0f, 0.0f};
  vec3 row_v{0.0f, 1.0f, 0.0f};

  BOUNCE_HD vec2 apply(vec2 uv) const {
    return {row_u.x * uv.x + row_u.y * uv.y + row_u.z, row_v.x * uv.x + row_v.y * uv.y + row_v.z};
  }
  // The extension's offset, rotation (radians) and scale, composed as it defines them.
  static TextureTransform from(vec2 offset, float rotation, vec2 scale) {
    const float c = std::cos(rotation), s = std::sin(rotation);
    TextureTransform t;
    t.row_u = {c * scale.x, -s * scale.y, offset.x};
    t.row_v = {s * scale.x, c * scale.y, offset.y};
    return t;
  }
};

// The most texels a texture may have (2^28, what image loading accepts): TextureView::sample
// indexes its floats with an int, which a loop over pixels then gathers with.
inline constexpr int64_t kMaxTexels = int64_t(1) << 28;

// The texels and the lookup, as plain data for kernels; Texture samples through it too.
struct TextureView {
  const vec3* texels = nullptr;  // row-major from the top row, linear RGB
  int width = 0;
  int height = 0;
  vec3 mean{0.0f};  // the texels' mean (mean_texel): what a lookup over the whole texture reads

  // A coordinate's position within its repeat, in [0, 1]: 1 only where rounding puts a tiny
  // negative coordinate there. Not finite (NaN, or infinite: inf - inf): 0.
  BOUNCE_HD static float repeat(float u) {
    const float f = u - std::floor(u);
    return ((f >= 0.0f) & (f <= 1.0f)) ? f : 0.0f;  // no branch: loops over pixels vectorise
  }

  // Bilinear, repeat wrapping; (0, 0) is the top-left texel's corner, as in glTF.
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 sample(vec2 uv) const {
    const float x = repeat(uv.x) * float(width) - 0.5f;
    const float y = repeat(uv.y) * float(height) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const float fx = x - float(x0), fy = y - float(y0);
    // Texel coordinates lie in [-1, size]: one step wraps them (integer division, twice per
    // coordinate, was most of a sample's cost on a textured level's G-buffer).
    const auto texel = [&](int tx, int ty) {
      tx = tx < 0 ? tx + width : (tx >= width ? tx - width : tx);
      ty = ty < 0 ? ty + height : (ty >= height ? ty - height : ty);
      const float* t = &texels[0].x;
      const int k = 3 * (ty * width + tx);  // < 3 * kMaxTexels: no overflow
      return vec3(t[k], t[k + 1], t[k + 2]);
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                    glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
  }
};

// Texture coordinates follow glTF: (0, 0) is the top-left texel of the image.
struct Texture {
  std::string name;  // usually the file it came from
  int width = 0;
  int height = 0;
  std::vector<vec3> texels;  // row-major from the top row, linear RGB

  // The mean is left 0: SceneData's views carry it (mean_texel), the host's lookups read texels.
  TextureView view() const { return {texels.data(), width, height}; }
  vec3 sample(vec2 uv) const { return view().sample(uv); }
};

// The mean of a texture's texels (0 for none).
vec3 mean_texel(const Texture& t);

}  // namespace bounce
