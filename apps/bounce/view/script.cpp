#include "script.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bounce/core/error.h"

namespace bounce::app {

namespace {

struct Verb {
  const char* name;
  int min_args, max_args;
  const char* synopsis;
};

constexpr Verb kScriptVerbs[] = {
    {"wait", 1, 1, "wait FRAMES            render FRAMES frames"},
    {"move", 3, 3, "move RIGHT UP FORWARD  move the camera (metres, camera axes)"},
    {"turn", 2, 2, "turn YAW PITCH         turn the camera (degrees)"},
    {"camera", 6, 6, "camera X Y Z TX TY TZ  place the camera at X Y Z looking at TX TY TZ"},
    {"flashlight", 1, 1, "flashlight on|off|toggle"},
    {"technique", 1, 1, "technique NAME         switch the indirect-light technique"},
    {"param", 2, 2, "param NAME VALUE       set a parameter of the technique or the denoiser"},
    {"denoise", 1, 1, "denoise on|off         temporal reuse and denoising"},
    {"show", 1, 1, "show VIEW              denoised, raw, history, motion or variance"},
    {"light", 3, 5,
     "light I position|color X Y Z   move or recolour light I (scene.lights)\n"
     "  light I rotation DEG          turn environment light I about +y"},
    {"object", 4, 4, "object I X Y Z         move mesh I by (X, Y, Z) metres"},
    {"exposure", 1, 1, "exposure EV"},
    {"play", 1, 1, "play on|off            play the scene's animation"},
    {"time", 1, 1, "time SECONDS           set the animation time"},
    {"path", 1, 1, "path on|off            follow the scene's camera path"},
    {"scale", 1, 1, "scale S                fixed internal resolution scale (0 < S <= 1)"},
    {"ui", 1, 1, "ui on|off              show the panel"},
    {"screenshot", 1, 1, "screenshot FILE.png    save the window as it is shown"},
    {"quit", 0, 0, "quit"},
};

const Verb* find_verb(const std::string& name) {
  for (const Verb& v : kScriptVerbs)
    if (name == v.name) return &v;
  return nullptr;
}

}  // namespace

float ScriptAction::number(size_t i) const {
  const std::string& text = args.at(i);
  char* end = nullptr;
  const float x = std::strtof(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x))
    fail("{}: {}: '{}' is not a number", where(), verb, text);
  return x;
}

int ScriptAction::integer(size_t i) const {
  const std::string& text = args.at(i);
  char* end = nullptr;
  const long x = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || x < 0 || x > 1000000)
    fail("{}: {}: '{}' is not a whole number in [0, 1000000]", where(), verb, text);
  return int(x);
}

bool ScriptAction::on_off(size_t i) const {
  const std::string& t = args.at(i);
  if (t == "on" || t == "true" || t == "1") return true;
  if (t == "off" || t == "false" || t == "0") return false;
  fail("{}: {}: expected on or off, found '{}'", where(), verb, t);
}

std::vector<ScriptAction> load_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("{}: cannot open the script", path);
  std::vector<ScriptAction> actions;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    ScriptAction a;
    a.file = path;
    a.line = line;
    if (!(words >> a.verb)) continue;
    for (std::string w; words >> w;) a.args.push_back(w);
    const Verb* v = find_verb(a.verb);
    if (!v) fail("{}: unknown action '{}' (see bounce view --help)", a.where(), a.verb);
    const int n = int(a.args.size());
    if (n < v->min_args || n > v->max_args)
      fail("{}: '{}' takes {} argument(s), found {}: {}", a.where(), a.verb, v->min_args, n,
           v->synopsis);
    if (a.verb == "flashlight" && a.args[0] != "toggle") a.on_off(0);
    if (a.verb == "denoise") a.on_off(0);
    if (a.verb == "show") parse_denoise_view(a.args[0], a.where());
    if (a.verb == "light" && a.args[1] != "position" && a.args[1] != "color" &&
        a.args[1] != "rotation")
      fail("{}: light: expected 'position', 'color' or 'rotation', found '{}'", a.where(),
           a.args[1]);
    if (a.verb == "light" && n != (a.args[1] == "rotation" ? 3 : 5))
      fail("{}: 'light I {}' takes {} number(s)", a.where(), a.args[1],
           a.args[1] == "rotation" ? 1 : 3);
    actions.push_back(std::move(a));
  }
  return actions;
}

const std::vector<std::pair<DenoiseView, std::string>>& denoise_view_names() {
  static const std::vector<std::pair<DenoiseView, std::string>> names = {
      {DenoiseView::kDenoised, "denoised"},
      {DenoiseView::kRaw, "raw"},
      {DenoiseView::kHistory, "history"},
      {DenoiseView::kMotion, "motion"},
      {DenoiseView::kVariance, "variance"}};
  return names;
}

DenoiseView parse_denoise_view(const std::string& name, const std::string& where) {
  for (const auto& [view, view_name] : denoise_view_names())
    if (name == view_name) return view;
  fail("{}: show: '{}' is not a view (denoised, raw, history, motion or variance)", where, name);
}

std::string script_help() {
  std::string text = "Script actions (--script FILE, one per line, '#' starts a comment):\n";
  for (const Verb& v : kScriptVerbs) text += fmt::format("  {}\n", v.synopsis);
  return text;
}

}  // namespace bounce::app
