#include "bounce/scene/quake/map_textures.h"

#include <algorithm>

// libstb ships the compiled implementation (linked through core), so only the declarations are
// included here.
#include <stb/stb_image.h>

#include <array>
#include <memory>

#include "bounce/core/color.h"
#include "bounce/core/error.h"

namespace bounce::quake {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c;
  return s;
}

std::string without_extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  return dot != std::string::npos && (slash == std::string::npos || dot > slash)
             ? path.substr(0, dot)
             : path;
}

// The entry names the game would try for an image path: as written, then .tga and .jpg.
std::vector<std::string> candidates(const std::string& image) {
  const std::string stem = without_extension(image);
  std::vector<std::string> out;
  if (stem != image) out.push_back(image);
  out.push_back(stem + ".tga");
  out.push_back(stem + ".jpg");
  return out;
}

struct StbFree {
  void operator()(unsigned char* p) const { stbi_image_free(p); }
};

// Decodes a .tga or .jpg held in memory to linear RGB (the images are sRGB) and, when `alpha` is
// given and the image has an alpha channel, its alpha (linear, in every channel); throws Error.
void decode(const std::string& name, const std::vector<uint8_t>& bytes, Texture& out,
            Texture* alpha) {
  if (bytes.size() > size_t(INT32_MAX)) fail("{}: the image is too large", name);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, StbFree> pixels(
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4));
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    fail("{}: corrupt or unsupported image{}", name,
         reason && *reason ? fmt::format(" (stb_image: {})", reason) : std::string());
  }
  if (w <= 0 || h <= 0 || int64_t(w) * h > (int64_t(1) << 26))
    fail("{}: image size {} x {} is out of range", name, w, h);
  static const std::array<float, 256> to_linear = [] {
    std::array<float, 256> t;
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_decode(float(i) / 255.0f);
    return t;
  }();
  out.width = w;
  out.height = h;
  out.texels.resize(size_t(w) * size_t(h));
  const unsigned char* p = pixels.get();
  for (vec3& t : out.texels) {
    t = vec3(to_linear[p[0]], to_linear[p[1]], to_linear[p[2]]);
    p += 4;
  }
  if (!alpha || (channels != 2 && channels != 4)) return;
  alpha->width = w;
  alpha->height = h;
  alpha->texels.resize(out.texels.size());
  p = pixels.get() + 3;
  for (vec3& t : alpha->texels) {
    t = vec3(float(*p) / 255.0f);
    p += 4;
  }
}

bool try_load(const Pk3Set& archives, const std::string& entry, int max_size, bool with_alpha,
              SurfaceImage& out) {
  const Pk3Archive* a = archives.find(entry);
  if (!a) return false;
  try {
    const std::vector<uint8_t> bytes = a->read(entry);
    decode(a->path() + ":" + entry, bytes, out.texture, with_alpha ? &out.alpha : nullptr);
    out.texture.name = entry;
    shrink_texture(out.texture, max_size);
    if (!out.alpha.texels.empty()) {
      out.alpha.name = entry + " (alpha)";
      shrink_texture(out.alpha, max_size);
    }
    out.average = mean_texel(out.texture);
    out.found = true;
    out.source = a->path() + ":" + entry;
    return true;
  } catch (const Error& e) {
    warn(e.what());
    return false;
  }
}

}  // namespace

ShaderTable read_shaders(const Pk3Set& archives, size_t* script_count) {
  ShaderTable table;
  size_t scripts = 0;
  for (const auto& a : archives.archives()) {
    for (const auto& name : a.names()) {
      const std::string l = lower(name);
      if (!l.starts_with("scripts/") || !l.ends_with(".shader")) continue;
      try {
        const std::vector<uint8_t> bytes = a.read(name);
        parse_shader_script(std::string(bytes.begin(), bytes.end()), a.path() + ":" + name, table);
        ++scripts;
      } catch (const Error& e) {
        warn(e.what());
      }
    }
  }
  if (script_count) *script_count = scripts;
  return table;
}

SurfaceImage find_surface_image(const Pk3Set& archives, const ShaderInfo* shader,
                                const std::string& name, int max_size, bool with_alpha) {
  SurfaceImage out;
  std::vector<std::string> images;
  if (shader && !shader->image.empty()) images.push_back(shader->image);
  images.push_back(name);
  if (shader && !shader->editor_image.empty()) images.push_back(shader->editor_image);
  for (const auto& image : images)
    for (const auto& entry : candidates(image))
      if (try_load(archives, entry, max_size, with_alpha, out)) return out;
  return out;
}

void shrink_texture(Texture& t, int max_size) {
  max_size = std::max(max_size, 1);
  while (t.width > max_size || t.height > max_size) {
    const int w = std::max(t.width / 2, 1), h = std::max(t.height / 2, 1);
    std::vector<vec3> out(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        vec3 sum(0.0f);
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = std::min(2 * x + dx, t.width - 1),
                      sy = std::min(2 * y + dy, t.height - 1);
            sum += t.texels[size_t(sy) * size_t(t.width) + size_t(sx)];
          }
        out[size_t(y) * size_t(w) + size_t(x)] = 0.25f * sum;
      }
    }
    t.texels = std::move(out);
    t.width = w;
    t.height = h;
  }
}

}  // namespace bounce::quake
