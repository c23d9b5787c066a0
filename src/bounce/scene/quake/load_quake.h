// Quake 3 levels as bounce scenes: "ARCHIVE.pk3:maps/NAME.bsp" (a map inside a .pk3) or a bare
// .bsp file. Geometry, textures, light entities, shader lights and the first spawn point as the
// camera; docs/quake.md describes the conversions and what is skipped.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bounce/scene/scene.h"

namespace bounce::quake {

class Pk3Set;

struct QuakeOptions {
  // More .pk3 files searched (first, in this order) for textures and shader scripts.
  std::vector<std::string> archives;
  // Also search the other .pk3 files in the map archive's folder, as the game searches its
  // folder (later names first: in the game they override earlier ones).
  bool sibling_archives = true;
  int patch_level = 4;         // quads along each side of a 3 x 3 Bezier patch
  int spawn = 0;               // which spawn point the camera starts at
  int max_texture_size = 256;  // larger images are halved until they fit (memory)
  bool full_textures = true;   // false: each material takes its texture's average colour
  float light_scale = 1.0f;    // multiplies every light the map brings
};

struct QuakeStats {
  std::array<size_t, 5> faces_by_type{};  // [1] polygons, [2] patches, [3] meshes, [4] billboards
  size_t faces_skipped = 0;               // sky, nodraw, fog, hint, decals, glows
  size_t patches = 0;                     // 3 x 3 Bezier patches tessellated
  size_t patch_triangles = 0;
  size_t triangles = 0;
  size_t point_lights = 0, spot_lights = 0, suns = 0, surface_light_shaders = 0;
  size_t spawn_points = 0;
  size_t textures = 0, textures_missing = 0, shaders = 0;
  size_t cutout_shaders = 0;  // alphaFunc surfaces (grates, foliage) read as alpha cut-outs
  size_t archives = 0;
};

struct QuakeMap {
  Scene scene;  // not yet finalized
  QuakeStats stats;
};

// True when `spec` names a map in an archive ("...pk3:...") or ends in .bsp.
bool is_quake_spec(const std::string& spec);

// Loads the map a spec names (see above); throws Error naming the file, lump or entry.
QuakeMap load_quake_map(const std::string& spec, const QuakeOptions& options = {});

// Builds the scene from .bsp bytes already in memory; textures and shaders come from
// `archives` (may be null: every surface is then grey). `name` is used in messages.
QuakeMap load_quake_bsp(std::span<const uint8_t> bytes, const std::string& name,
                        const QuakeOptions& options, const Pk3Set* archives);

}  // namespace bounce::quake
