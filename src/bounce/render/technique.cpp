#include "bounce/render/technique.h"

namespace bounce {

TechniqueOption param_option(const std::string& flag, const std::string& param,
                             const std::string& help) {
  return {flag, help,
          [param](ParamSet& params, const std::string& text) { params.set(param, text); }};
}

}  // namespace bounce
