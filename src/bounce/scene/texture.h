// An RGB texture in linear colour, sampled bilinearly with repeat wrapping, from a chain of
// box-filtered levels (mipmaps) where a lookup's footprint covers many texels.
#pragma once

#include <bit>
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
  // How much it scales a small width: the square root of how much it scales areas.
  BOUNCE_HD float scale() const {
    return std::sqrt(std::fabs(row_u.x * row_v.y - row_u.y * row_v.x));
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

// The most levels a texture's chain keeps: level 15 of the largest texture kMaxTexels allows
// (16384 x 16384) is its 1 x 1 mean; a long thin texture's chain stops at a strip.
inline constexpr int kMaxTextureLevels = 15;

// log2(x) for x >= 1 from the float's exponent and its mantissa taken as linear (at most 0.09
// off between powers of two, exact at them): the level of detail needs no more, and it
// vectorises where libm's would not.
BOUNCE_HD BOUNCE_LANE_INLINE float coarse_log2(float x) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const float mantissa = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
  return float(int32_t(bits >> 23) - 127) + (mantissa - 1.0f);
}

// The texels and the lookup, as plain data for kernels; Texture samples through it too.
struct TextureView {
  const vec3* texels = nullptr;  // row-major from the top row, linear RGB: level 0, then the rest
  int width = 0;
  int height = 0;
  vec3 mean{0.0f};  // the texels' mean (mean_texel): what a lookup over the whole texture reads
  // Levels in the chain (1: level 0 alone) and where each starts in `texels`. Level k is
  // max(width >> k, 1) x max(height >> k, 1), each texel the mean of the block of level k - 1
  // it covers (build_texture_levels).
  int levels = 1;
  int level_offset[kMaxTextureLevels] = {};

  BOUNCE_HD int level_width(int k) const { return glm::max(width >> k, 1); }
  BOUNCE_HD int level_height(int k) const { return glm::max(height >> k, 1); }

  // A coordinate's position within its repeat, in [0, 1]: 1 only where rounding puts a tiny
  // negative coordinate there. Not finite (NaN, or infinite: inf - inf): 0.
  BOUNCE_HD static float repeat(float u) {
    const float f = u - std::floor(u);
    return ((f >= 0.0f) & (f <= 1.0f)) ? f : 0.0f;  // no branch: loops over pixels vectorise
  }

  // Bilinear, repeat wrapping; (0, 0) is the top-left texel's corner, as in glTF.
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 sample(vec2 uv) const {
    return sample_level(uv, texels, 0, width, height);
  }

  // For a footprint `uv_width` wide in texture coordinates (0: level 0 alone, as sample(uv)):
  // bilinear on the finer of the two levels around the one where the footprint spans a texel.
  // (Blending the two, trilinear, cost a level's G-buffer at 1280x720 4 ms more, a quarter; the
  // nearer of the two blurred more than the reference: docs/benchmarks.md, stop 49.)
  BOUNCE_HD BOUNCE_LANE_INLINE vec3 sample(vec2 uv, float uv_width) const {
    const float across = uv_width * std::sqrt(float(width) * float(height));
    // (Not a number, from absurd texture coordinates: level 0; infinite: the last level.)
    const float lod = coarse_log2(across >= 1.0f ? across : 1.0f);
    const int k = glm::min(int(lod), levels - 1);
    return sample_level(uv, texels, level_offset[k], level_width(k), level_height(k));
  }

  // Bilinear on one level of `width` x `height` texels, `offset` texels into `texels` (an index,
  // not a moved pointer: a loop over pixels gathers from one base).
  BOUNCE_HD BOUNCE_LANE_INLINE static vec3 sample_level(vec2 uv, const vec3* texels, int offset,
                                                        int width, int height) {
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
      const int k = 3 * (offset + ty * width + tx);  // < 4 * kMaxTexels: no overflow
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
  // (Level 0 alone: the host's lookups are the path tracer's, which wants every texel.)
  TextureView view() const { return {texels.data(), width, height}; }
  vec3 sample(vec2 uv) const { return view().sample(uv); }
  vec3 sample(vec2 uv, float) const { return view().sample(uv); }
};

// The texels of `width` x `height` texels' chain (every level), at most kMaxTextureLevels levels.
size_t texture_chain_texels(int width, int height);

// Writes the levels after level 0 of `view` (whose texels, writable, hold level 0 and room for
// the chain: texture_chain_texels) and sets its levels and offsets.
void build_texture_levels(TextureView& view, vec3* texels);

// The mean of a texture's texels (0 for none).
vec3 mean_texel(const Texture& t);

}  // namespace bounce
