#include "build_info.h"

#include <fstream>
#include <thread>

#ifndef BOUNCE_VERSION
#define BOUNCE_VERSION "unknown"
#endif
#ifndef BOUNCE_GIT_REVISION
#define BOUNCE_GIT_REVISION "unknown"
#endif
#ifndef BOUNCE_BUILD_TYPE
#define BOUNCE_BUILD_TYPE "unknown"
#endif

namespace bounce::app {

BuildInfo build_info() {
  BuildInfo b;
  b.version = BOUNCE_VERSION;
#if defined(__clang__)
  b.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  b.compiler = "gcc " __VERSION__;
#else
  b.compiler = "unknown";
#endif
  b.build_type = BOUNCE_BUILD_TYPE;
  b.git_revision = BOUNCE_GIT_REVISION;
  return b;
}

MachineInfo machine_info() {
  MachineInfo m;
  m.cpu = "unknown";
  m.logical_cores = int(std::thread::hardware_concurrency());
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("model name")) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const size_t start = line.find_first_not_of(" \t", colon + 1);
    if (start != std::string::npos) m.cpu = line.substr(start);
    break;
  }
  return m;
}

}  // namespace bounce::app
