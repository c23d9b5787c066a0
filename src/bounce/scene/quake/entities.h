// The entity lump of a Quake 3 map: blocks of quoted "key" "value" pairs in braces.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bounce/core/math.h"

namespace bounce::quake {

struct Entity {
  std::vector<std::pair<std::string, std::string>> pairs;

  // The value of the first pair with this key (keys match without regard to case).
  std::optional<std::string> get(const std::string& key) const;
  std::string classname() const { return get("classname").value_or(""); }
  // A number or three numbers ("x y z"); nullopt when absent or not numbers.
  std::optional<float> number(const std::string& key) const;
  std::optional<vec3> vector(const std::string& key) const;
};

// Parses the entity text; throws Error naming `name`, the lump and the line of a syntax error
// (an unterminated string or block, a key without a value, text outside a block).
std::vector<Entity> parse_entities(const std::string& text, const std::string& name);

}  // namespace bounce::quake
