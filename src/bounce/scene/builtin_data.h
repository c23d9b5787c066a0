// The Cornell box OBJ and MTL text, compiled in from scenes/cornell-box by CMake.
#pragma once

namespace bounce::builtin_data {
extern const char* const kCornellObj;
extern const char* const kCornellMtl;
}  // namespace bounce::builtin_data
