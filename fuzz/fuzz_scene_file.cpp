// A scene file (*.bounce.json): lights, cameras, animation keys and models (built-in ones, so the
// input alone decides what loads), then validation and a tiny frame.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  bounce::fuzz::load_and_render(bounce::fuzz::scratch_file(data, size, ".bounce.json"));
  return 0;
}
