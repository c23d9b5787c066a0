// Running the bounce program from tests: its exit status and output, and scratch directories.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "test_text.h"

namespace bounce::cli_test {

using test::contains;

struct Result {
  int status = -1;     // exit status; -1 when the program did not exit normally (a crash)
  std::string output;  // stdout, and stderr unless left out
};

inline Result run(const std::string& args, bool with_stderr = true) {
  const std::string command =
      std::string(BOUNCE_APP_PATH) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  Result r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// An empty directory under the system's temporary directory.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("bounce-cli-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace bounce::cli_test
