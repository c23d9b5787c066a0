// OBJ and its material library, in memory: the input is the OBJ text, then optionally a line
// "#mtl" and the MTL text the OBJ's usemtl statements refer to.
#include <string>

#include "bounce/core/error.h"
#include "bounce/scene/load.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("\n#mtl\n");
  const std::string obj = split == std::string::npos ? text : text.substr(0, split);
  const std::string mtl = split == std::string::npos ? std::string() : text.substr(split + 6);
  try {
    bounce::Scene scene = bounce::load_obj_text(obj, mtl, "fuzz.obj");
    scene.finalize();
    bounce::fuzz::render_tiny(scene);
  } catch (const bounce::Error&) {
  }
  return 0;
}
