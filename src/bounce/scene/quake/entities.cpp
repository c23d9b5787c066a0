#include "bounce/scene/quake/entities.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "bounce/core/error.h"

namespace bounce::quake {

namespace {

bool same_key(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

// Reads whitespace-separated floats; fails unless exactly `n` finite numbers are there.
bool parse_floats(const std::string& s, float* out, int n) {
  const char* p = s.c_str();
  for (int i = 0; i < n; ++i) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v) || std::fabs(v) > 1e30) return false;
    out[i] = float(v);
    p = end;
  }
  while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
  return *p == '\0';
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& name) : s_(text), name_(name) {}

  std::vector<Entity> all() {
    std::vector<Entity> out;
    while (skip_space()) {
      if (s_[i_] != '{') syntax("expected '{' to open an entity");
      ++i_;
      Entity e;
      for (;;) {
        if (!skip_space()) syntax("an entity is not closed by '}'");
        if (s_[i_] == '}') {
          ++i_;
          break;
        }
        std::string key = quoted("a key");
        if (!skip_space() || s_[i_] != '"') syntax("key '" + key + "' has no value");
        std::string value = quoted("a value");
        e.pairs.emplace_back(std::move(key), std::move(value));
      }
      out.push_back(std::move(e));
    }
    return out;
  }

 private:
  bool skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) {
      if (s_[i_] == '\n') ++line_;
      ++i_;
    }
    return i_ < s_.size();
  }
  std::string quoted(const char* what) {
    if (s_[i_] != '"') syntax(std::string("expected a quoted string for ") + what);
    const size_t start = ++i_;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\n') syntax("a string runs past the end of its line");
      ++i_;
    }
    if (i_ >= s_.size()) syntax("a string is not terminated");
    return s_.substr(start, i_++ - start);
  }
  [[noreturn]] void syntax(const std::string& what) const {
    fail("{}: lump 'entities', line {}: {}", name_, line_, what);
  }

  const std::string& s_;
  const std::string& name_;
  size_t i_ = 0;
  int line_ = 1;
};

}  // namespace

std::optional<std::string> Entity::get(const std::string& key) const {
  for (const auto& [k, v] : pairs)
    if (same_key(k, key)) return v;
  return std::nullopt;
}

std::optional<float> Entity::number(const std::string& key) const {
  const auto v = get(key);
  float x = 0.0f;
  if (!v || !parse_floats(*v, &x, 1)) return std::nullopt;
  return x;
}

std::optional<vec3> Entity::vector(const std::string& key) const {
  const auto v = get(key);
  float x[3];
  if (!v || !parse_floats(*v, x, 3)) return std::nullopt;
  return vec3(x[0], x[1], x[2]);
}

std::vector<Entity> parse_entities(const std::string& text, const std::string& name) {
  return Parser(text, name).all();
}

}  // namespace bounce::quake
