// Quake 3 shader scripts (scripts/*.shader): only what a photon mapper needs from them. A
// shader names the image its surface shows, and may make the surface a light
// (q3map_surfacelight), the sky's sun (q3map_sun) or an effect that is not matter at all.
#pragma once

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "bounce/core/math.h"

namespace bounce::quake {

struct Sun {
  vec3 colour{1.0f};
  float intensity = 0.0f;  // q3map's units
  float azimuth_deg = 0.0f, elevation_deg = 0.0f;
};

// A stage's alphaFunc: which texels of its image are drawn (the others are holes).
enum class AlphaTest : uint8_t {
  kNone,
  kGreaterThanZero,  // GT0
  kAtLeastHalf,      // GE128
  kBelowHalf,        // LT128: the inverse of GE128, which cut-outs cannot express
};

struct ShaderInfo {
  std::string image;         // the first stage's map / clampMap / animMap image, if any
  std::string editor_image;  // qer_editorimage: the editor's preview, a fallback
  std::string light_image;   // q3map_lightimage: the image whose colour the light takes
  float surface_light = 0.0f;
  std::optional<Sun> sun;
  bool sky = false, nodraw = false, fog = false;
  int stages = 0;         // rendering stages ({ ... } blocks)
  bool decal = false;     // polygonOffset: drawn over another surface
  bool additive = false;  // every stage adds to what is behind it: a glow, not matter
  AlphaTest alpha_test = AlphaTest::kNone;  // the first stage's with an alphaFunc
};

// Shader name (lower case) -> what it says.
using ShaderTable = std::unordered_map<std::string, ShaderInfo>;

// Adds the shaders of one script to `table` (an earlier definition of a name wins, as in the
// game). A syntax error stops reading this script with a warning naming `file` and the line; the
// shaders read before it are kept.
void parse_shader_script(const std::string& text, const std::string& file, ShaderTable& table);

}  // namespace bounce::quake
