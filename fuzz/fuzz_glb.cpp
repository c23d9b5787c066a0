// glTF 2.0 as a .glb file: tinygltf's parser, our preflight, buffers, nodes, materials and
// animation, then validation and a tiny frame.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  bounce::fuzz::load_and_render(bounce::fuzz::scratch_file(data, size, ".glb"));
  return 0;
}
