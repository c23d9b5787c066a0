// The images of a Quake 3 map's surfaces, found in its .pk3 archives as the game finds them:
// the shader's image if a script names one, else the texture name with .tga, then .jpg.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "bounce/scene/quake/pk3.h"
#include "bounce/scene/quake/shaders.h"
#include "bounce/scene/texture.h"

namespace bounce::quake {

struct SurfaceImage {
  bool found = false;
  Texture texture;     // linear RGB, at most max_size texels on a side
  Texture alpha;       // the alpha channel in every channel, when asked for and the image has one
  vec3 average{0.5f};  // the texels' mean (grey when not found)
  std::string source;  // archive entry it came from
};

// Shader scripts of all archives, earlier archives first (their definitions win).
ShaderTable read_shaders(const Pk3Set& archives, size_t* script_count);

// The image of texture `name` (no extension), or found = false. Unreadable images are a
// warning, not an error: the surface is then grey. `with_alpha` also keeps the alpha channel.
SurfaceImage find_surface_image(const Pk3Set& archives, const ShaderInfo* shader,
                                const std::string& name, int max_size, bool with_alpha = false);

// Halves a texture (2 x 2 box filter) until neither side exceeds max_size.
void shrink_texture(Texture& t, int max_size);

}  // namespace bounce::quake
