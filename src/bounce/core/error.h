// One error type for bad input: the message names the file (or argument) and the problem.
#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace bounce {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// Prints a warning to stderr (the one place warnings go, so tests and tools can capture them).
void warn(const std::string& message);

}  // namespace bounce
