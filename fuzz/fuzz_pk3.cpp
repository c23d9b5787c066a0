// A .pk3 (zip) archive: the central directory, every entry read and decompressed, and the first
// maps/*.bsp in it loaded as a level whose textures and shader scripts come from the same archive
// (not its folder's siblings: the input alone decides what loads), then a tiny frame.
#include <string>

#include "bounce/core/error.h"
#include "bounce/scene/quake/load_quake.h"
#include "bounce/scene/quake/pk3.h"
#include "fuzz_common.h"

namespace {

bool is_map(const std::string& name) {
  return name.size() > 9 && name.compare(0, 5, "maps/") == 0 &&
         name.compare(name.size() - 4, 4, ".bsp") == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = bounce::fuzz::scratch_file(data, size, ".pk3");
  try {
    const bounce::quake::Pk3Archive archive(path);
    std::string map;
    for (const std::string& name : archive.names()) {
      try {
        archive.read(name);
      } catch (const bounce::Error&) {  // one bad entry; the others are still read
      }
      if (map.empty() && is_map(name)) map = name;
    }
    if (map.empty()) return 0;
    bounce::quake::QuakeOptions options;
    options.sibling_archives = false;
    options.max_texture_size = 16;
    bounce::Scene scene = bounce::quake::load_quake_map(path + ":" + map, options).scene;
    scene.finalize();
    bounce::fuzz::render_tiny(scene);
  } catch (const bounce::Error&) {
  }
  return 0;
}
