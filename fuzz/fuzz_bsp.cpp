// A Quake 3 level (IBSP 46) as a bare .bsp: every lump's counts, offsets and indices, Bezier
// patches, entities and lights, then validation and a tiny frame (textures grey: no archives).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  bounce::fuzz::load_and_render(bounce::fuzz::scratch_file(data, size, ".bsp"));
  return 0;
}
