#include "bounce/render/params_file.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "bounce/core/error.h"

namespace bounce {

std::vector<std::string> read_params_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("{}: cannot open the parameter file", path);
  nlohmann::ordered_json json;
  try {
    json = nlohmann::ordered_json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not valid JSON ({})", path, e.what());
  }
  if (!json.is_object()) fail("{}: a parameter file is a JSON object of name: value", path);
  std::vector<std::string> assignments;
  for (const auto& [name, value] : json.items()) {
    std::string text;
    if (value.is_boolean())
      text = value.get<bool>() ? "true" : "false";
    else if (value.is_number_integer())
      text = fmt::format("{}", value.get<int64_t>());
    else if (value.is_number())
      text = fmt::format("{}", value.get<double>());
    else if (value.is_string())
      text = value.get<std::string>();
    else
      fail("{}: parameter '{}' is not a number, boolean or string", path, name);
    assignments.push_back(name + "=" + text);
  }
  return assignments;
}

}  // namespace bounce
