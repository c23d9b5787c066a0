// Parameter files: a technique's (and the denoiser's) parameters set from a small JSON file
// instead of flags, as the seed's configuration file set its 16 parameters without recompiling.
#pragma once

#include <string>
#include <vector>

namespace bounce {

// Reads a JSON object of names and values ({"photons_from_light": 400, "use_sphere_slice":
// true}) as "name=value" assignments in file order, for ParamSet::set_assignment (or the CLI's
// --param). Throws Error naming the file on a missing file, bad JSON or a value that is not a
// number, boolean or string.
std::vector<std::string> read_params_file(const std::string& path);

}  // namespace bounce
