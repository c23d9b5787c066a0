// The technique registry: the one place that maps names to implementations.
#include "bounce/techniques/registry.h"

#include <functional>
#include <utility>

#include "bounce/core/error.h"
#include "bounce/techniques/direct/direct_only.h"
#include "bounce/techniques/lhb/lhb.h"
#include "bounce/techniques/path/path_technique.h"
#include "bounce/techniques/registry.h"
#include "bounce/techniques/tiled/tiled.h"
#include "bounce/techniques/vertex/vertex.h"

namespace bounce {

namespace {

using Factory = std::function<std::unique_ptr<Technique>()>;

const std::vector<std::pair<std::string, Factory>>& registry() {
  static const std::vector<std::pair<std::string, Factory>> techniques = {
      {"direct", [] { return std::make_unique<DirectOnly>(); }},
      {"lhb", [] { return std::make_unique<LhbTechnique>(); }},
      {"path", [] { return std::make_unique<PathTracing>(); }},
      {"tiled", [] { return std::make_unique<TiledPhotonMapping>(); }},
      {"vertex", [] { return std::make_unique<VertexPhotonMapping>(); }},
  };
  return techniques;
}

}  // namespace

std::vector<std::string> technique_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

std::unique_ptr<Technique> make_technique(const std::string& name) {
  for (const auto& [known, factory] : registry())
    if (known == name) return factory();
  std::string list;
  for (const auto& n : technique_names()) list += (list.empty() ? "" : ", ") + n;
  fail("unknown technique '{}' (known: {})", name, list);
}

}  // namespace bounce
