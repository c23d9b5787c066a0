// The loaders that read a file by path, one target each (fuzz/CMakeLists.txt defines
// BOUNCE_FUZZ_EXTENSION): the input is written to a scratch file with that extension and goes
// through load_scene (the loader, then the validation every scene gets) and a tiny frame.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  bounce::fuzz::load_and_render(bounce::fuzz::scratch_file(data, size, BOUNCE_FUZZ_EXTENSION));
  return 0;
}
