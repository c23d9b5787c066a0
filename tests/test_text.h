// Text checks shared by the tests of every folder (error messages, command output).
#pragma once

#include <string>

namespace bounce::test {

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace bounce::test
