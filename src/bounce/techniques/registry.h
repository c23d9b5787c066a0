// The technique registry: every technique by name, for the CLI, the viewer and the evaluation runs.
// It lives above render/ because it must know every technique; render/ only knows the interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bounce/render/technique.h"

namespace bounce {

// Creates a technique by name; throws Error listing the known names for an unknown one.
std::unique_ptr<Technique> make_technique(const std::string& name);
std::vector<std::string> technique_names();

}  // namespace bounce
