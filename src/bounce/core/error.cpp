#include "bounce/core/error.h"

#include <cstdio>

namespace bounce {

void warn(const std::string& message) {
  fmt::print(stderr, "bounce: warning: {}\n", message);
}

}  // namespace bounce
