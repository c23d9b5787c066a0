#include "bounce/core/input_file.h"

#include <filesystem>
#include <system_error>

#include "bounce/core/error.h"

namespace bounce {

namespace {
namespace fs = std::filesystem;

const char* kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    case fs::file_type::fifo:
      return "a fifo";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}
}  // namespace

void check_regular_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);  // follows links, as opening would
  if (ec || !fs::exists(status)) fail("{}: {} not found", path, what);
  if (!fs::is_regular_file(status))
    fail("{}: {} is {}, not a regular file", path, what, kind_of(status.type()));
}

bool exists_but_not_regular(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  return !ec && fs::exists(status) && !fs::is_regular_file(status);
}

}  // namespace bounce
