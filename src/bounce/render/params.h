// Named, bounded tuning parameters of a technique or stage, settable by name from the CLI
// (--param name=value) and, later, from the viewer's panel.
#pragma once

#include <string>
#include <vector>

namespace bounce {

struct Param {
  enum class Kind { kFloat, kInt, kBool };
  std::string name;
  std::string help;
  Kind kind = Kind::kFloat;
  void* value = nullptr;  // float*, int* or bool*, owned by the technique
  double min = 0.0;
  double max = 0.0;

  std::string to_string() const;
};

class ParamSet {
 public:
  void add_float(const std::string& name, float* value, double min, double max,
                 const std::string& help);
  void add_int(const std::string& name, int* value, int min, int max, const std::string& help);
  void add_bool(const std::string& name, bool* value, const std::string& help);

  // Parses and range-checks `text`; throws Error naming the parameter on a bad name or value.
  void set(const std::string& name, const std::string& text);
  // Parses "name=value".
  void set_assignment(const std::string& assignment);
  const Param* find(const std::string& name) const;
  const std::vector<Param>& all() const { return params_; }

 private:
  std::vector<Param> params_;
};

}  // namespace bounce
