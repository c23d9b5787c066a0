// What a benchmark record says about the build and the machine it ran on.
#pragma once

#include <string>

namespace bounce::app {

struct BuildInfo {
  std::string version;       // the bounce project version
  std::string compiler;      // compiler name and version
  std::string build_type;    // CMake build type
  std::string git_revision;  // `git describe --always --dirty` when CMake configured the build
};

struct MachineInfo {
  std::string cpu;  // model name from /proc/cpuinfo ("unknown" where unavailable)
  int logical_cores = 0;
};

BuildInfo build_info();
MachineInfo machine_info();

}  // namespace bounce::app
