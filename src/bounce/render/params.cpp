#include "bounce/render/params.h"

#include <cmath>
#include <cstdlib>

#include "bounce/core/error.h"

namespace bounce {

std::string Param::to_string() const {
  switch (kind) {
    case Kind::kFloat:
      return fmt::format("{}", *static_cast<float*>(value));
    case Kind::kInt:
      return fmt::format("{}", *static_cast<int*>(value));
    case Kind::kBool:
      return *static_cast<bool*>(value) ? "true" : "false";
  }
  return "";
}

void ParamSet::add_float(const std::string& name, float* value, double min, double max,
                         const std::string& help) {
  params_.push_back({name, help, Param::Kind::kFloat, value, min, max});
}

void ParamSet::add_int(const std::string& name, int* value, int min, int max,
                       const std::string& help) {
  params_.push_back({name, help, Param::Kind::kInt, value, double(min), double(max)});
}

void ParamSet::add_bool(const std::string& name, bool* value, const std::string& help) {
  params_.push_back({name, help, Param::Kind::kBool, value, 0.0, 1.0});
}

const Param* ParamSet::find(const std::string& name) const {
  for (const auto& p : params_)
    if (p.name == name) return &p;
  return nullptr;
}

void ParamSet::set(const std::string& name, const std::string& text) {
  const Param* p = find(name);
  if (!p) {
    std::string known;
    for (const auto& q : params_) known += (known.empty() ? "" : ", ") + q.name;
    fail("unknown parameter '{}' (known: {})", name, known.empty() ? "none" : known);
  }
  if (p->kind == Param::Kind::kBool) {
    if (text == "true" || text == "1" || text == "on")
      *static_cast<bool*>(p->value) = true;
    else if (text == "false" || text == "0" || text == "off")
      *static_cast<bool*>(p->value) = false;
    else
      fail("parameter '{}': '{}' is not a boolean (true/false)", name, text);
    return;
  }
  const char* begin = text.data();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || !std::isfinite(v))
    fail("parameter '{}': '{}' is not a number", name, text);
  if (p->kind == Param::Kind::kInt && v != double(int64_t(v)))
    fail("parameter '{}': '{}' is not an integer", name, text);
  if (v < p->min || v > p->max)
    fail("parameter '{}': {} is outside [{}, {}]", name, text, p->min, p->max);
  if (p->kind == Param::Kind::kInt)
    *static_cast<int*>(p->value) = int(v);
  else
    *static_cast<float*>(p->value) = float(v);
}

void ParamSet::set_assignment(const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    fail("parameter '{}' is not of the form name=value", assignment);
  set(assignment.substr(0, eq), assignment.substr(eq + 1));
}

}  // namespace bounce
