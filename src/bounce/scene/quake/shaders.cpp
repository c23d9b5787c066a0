#include "bounce/scene/quake/shaders.h"

#include <cctype>
#include <cstdlib>

#include "bounce/core/error.h"

namespace bounce::quake {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Tokens of one line at a time: shader syntax is a keyword and its arguments up to the end of
// the line, with braces opening and closing blocks. Comments are // and /* */.
class Tokens {
 public:
  explicit Tokens(const std::string& s) : s_(s) {}

  // The next token, or "" at the end; sets new_line when a line break came before it.
  std::string next(bool* new_line) {
    *new_line = false;
    for (;;) {
      while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) {
        if (s_[i_] == '\n') {
          *new_line = true;
          ++line_;
        }
        ++i_;
      }
      if (s_.compare(i_, 2, "//") == 0) {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
        continue;
      }
      if (s_.compare(i_, 2, "/*") == 0) {
        const size_t end = s_.find("*/", i_ + 2);
        for (size_t k = i_; k < std::min(end, s_.size()); ++k) line_ += s_[k] == '\n';
        i_ = end == std::string::npos ? s_.size() : end + 2;
        continue;
      }
      break;
    }
    if (i_ >= s_.size()) return "";
    if (s_[i_] == '{' || s_[i_] == '}') return std::string(1, s_[i_++]);
    if (s_[i_] == '"') {
      const size_t end = s_.find('"', i_ + 1);
      const size_t stop = end == std::string::npos ? s_.size() : end;
      std::string t = s_.substr(i_ + 1, stop - i_ - 1);
      i_ = stop + 1;
      return t;
    }
    const size_t start = i_;
    while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) && s_[i_] != '{' &&
           s_[i_] != '}')
      ++i_;
    return s_.substr(start, i_ - start);
  }
  // The rest of the current line's tokens.
  std::vector<std::string> rest_of_line() {
    std::vector<std::string> out;
    for (;;) {
      const size_t save_i = i_;
      const int save_line = line_;
      bool new_line = false;
      std::string t = next(&new_line);
      if (t.empty() || new_line || t == "{" || t == "}") {
        i_ = save_i;
        line_ = save_line;
        return out;
      }
      out.push_back(std::move(t));
    }
  }
  int line() const { return line_; }

 private:
  const std::string& s_;
  size_t i_ = 0;
  int line_ = 1;
};

float number(const std::vector<std::string>& args, size_t i) {
  return i < args.size() ? std::strtof(args[i].c_str(), nullptr) : 0.0f;
}

bool is_additive(const std::vector<std::string>& args) {
  if (args.empty()) return false;
  const std::string a = lower(args[0]);
  if (a == "add") return true;
  return args.size() >= 2 && a == "gl_one" && lower(args[1]) == "gl_one";
}

AlphaTest alpha_test(const std::vector<std::string>& args) {
  const std::string a = args.empty() ? std::string() : lower(args[0]);
  if (a == "gt0") return AlphaTest::kGreaterThanZero;
  if (a == "ge128") return AlphaTest::kAtLeastHalf;
  if (a == "lt128") return AlphaTest::kBelowHalf;
  return AlphaTest::kNone;
}

// Reads one stage block (after its '{'): the image, whether it blends additively and its alpha
// test.
void read_stage(Tokens& t, ShaderInfo& info, bool* additive, const std::string& file) {
  bool new_line = false;
  for (;;) {
    const std::string token = t.next(&new_line);
    if (token.empty()) fail("{}: line {}: a stage is not closed by '}}'", file, t.line());
    if (token == "}") return;
    if (token == "{") fail("{}: line {}: a block inside a stage", file, t.line());
    const std::string key = lower(token);
    std::vector<std::string> args = t.rest_of_line();
    if ((key == "map" || key == "clampmap") && !args.empty() && args[0][0] != '$' &&
        info.image.empty())
      info.image = args[0];
    if (key == "animmap" && args.size() >= 2 && info.image.empty()) info.image = args[1];
    if (key == "blendfunc") *additive = is_additive(args);
    if (key == "alphafunc" && info.alpha_test == AlphaTest::kNone)
      info.alpha_test = alpha_test(args);
  }
}

// Reads one shader body (after its '{').
ShaderInfo read_shader(Tokens& t, const std::string& file) {
  ShaderInfo info;
  bool any_stage = false, all_additive = true;
  bool new_line = false;
  for (;;) {
    const std::string token = t.next(&new_line);
    if (token.empty()) fail("{}: line {}: a shader is not closed by '}}'", file, t.line());
    if (token == "}") break;
    if (token == "{") {
      bool additive = false;
      read_stage(t, info, &additive, file);
      any_stage = true;
      ++info.stages;
      all_additive = all_additive && additive;
      continue;
    }
    const std::string key = lower(token);
    const std::vector<std::string> args = t.rest_of_line();
    if (key == "surfaceparm" && !args.empty()) {
      const std::string p = lower(args[0]);
      info.sky |= p == "sky";
      info.nodraw |= p == "nodraw";
      info.fog |= p == "fog";
    } else if (key == "q3map_surfacelight") {
      info.surface_light = number(args, 0);
    } else if (key == "q3map_lightimage" && !args.empty()) {
      info.light_image = args[0];
    } else if (key == "qer_editorimage" && !args.empty()) {
      info.editor_image = args[0];
    } else if (key == "polygonoffset") {
      info.decal = true;
    } else if ((key == "q3map_sun" || key == "q3map_sunext") && args.size() >= 6) {
      Sun sun;
      sun.colour = vec3(number(args, 0), number(args, 1), number(args, 2));
      sun.intensity = number(args, 3);
      sun.azimuth_deg = number(args, 4);
      sun.elevation_deg = number(args, 5);
      info.sun = sun;
    }
  }
  info.additive = any_stage && all_additive;
  return info;
}

}  // namespace

void parse_shader_script(const std::string& text, const std::string& file, ShaderTable& table) {
  Tokens t(text);
  try {
    bool new_line = false;
    for (;;) {
      const std::string name = t.next(&new_line);
      if (name.empty()) return;
      if (name == "{" || name == "}")
        fail("{}: line {}: expected a shader name, found '{}'", file, t.line(), name);
      if (t.next(&new_line) != "{")
        fail("{}: line {}: shader '{}' has no body", file, t.line(), name);
      ShaderInfo info = read_shader(t, file);
      table.emplace(lower(name), std::move(info));
    }
  } catch (const Error& e) {
    warn(std::string(e.what()) + "; the rest of the script is skipped");
  }
}

}  // namespace bounce::quake
