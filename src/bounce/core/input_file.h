// Input files: only regular files are read. A device (/dev/zero), fifo or directory named as a
// model, material, texture or scene would hang the reader or fill memory without end.
#pragma once

#include <string>

namespace bounce {

// Throws Error when `path` does not exist or is not a regular file; `what` says what the file is
// for ("OBJ", "material file", ...) in the message.
void check_regular_file(const std::string& path, const std::string& what);

// Whether `path` exists but is not a regular file (a device, fifo, socket or directory).
bool exists_but_not_regular(const std::string& path);

}  // namespace bounce
