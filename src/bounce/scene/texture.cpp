#include "bounce/scene/texture.h"

namespace bounce {

vec3 mean_texel(const Texture& t) {
  glm::dvec3 sum(0.0);
  for (const vec3& v : t.texels) sum += glm::dvec3(v);
  return t.texels.empty() ? vec3(0.0f) : vec3(sum / double(t.texels.size()));
}

namespace {

// Levels until both sides are 1 texel, at most kMaxTextureLevels.
int level_count(int width, int height) {
  int levels = 1;
  while (levels < kMaxTextureLevels && (width >> (levels - 1) > 1 || height >> (levels - 1) > 1))
    ++levels;
  return levels;
}

}  // namespace

size_t texture_chain_texels(int width, int height) {
  TextureView v;
  v.width = width;
  v.height = height;
  size_t texels = 0;
  for (int k = 0; k < level_count(width, height); ++k)
    texels += size_t(v.level_width(k)) * size_t(v.level_height(k));
  return texels;
}

void build_texture_levels(TextureView& view, vec3* texels) {
  view.levels = view.width > 0 && view.height > 0 ? level_count(view.width, view.height) : 1;
  view.level_offset[0] = 0;
  for (int k = 1; k < view.levels; ++k) {
    const int sw = view.level_width(k - 1), sh = view.level_height(k - 1);
    const int w = view.level_width(k), h = view.level_height(k);
    view.level_offset[k] = view.level_offset[k - 1] + sw * sh;
    const vec3* src = texels + view.level_offset[k - 1];
    vec3* dst = texels + view.level_offset[k];
    // Each texel is the mean of the source texels its area covers: a 2 x 2 block, or 3 wide or
    // tall at the end of an odd side (and 1 where a side is already 1).
    for (int y = 0; y < h; ++y) {
      const int y0 = y * sh / h, y1 = (y + 1) * sh / h;
      for (int x = 0; x < w; ++x) {
        const int x0 = x * sw / w, x1 = (x + 1) * sw / w;
        vec3 sum(0.0f);
        for (int sy = y0; sy < y1; ++sy)
          for (int sx = x0; sx < x1; ++sx) sum += src[size_t(sy) * size_t(sw) + size_t(sx)];
        dst[size_t(y) * size_t(w) + size_t(x)] = sum / float((x1 - x0) * (y1 - y0));
      }
    }
  }
  view.texels = texels;
}

}  // namespace bounce
