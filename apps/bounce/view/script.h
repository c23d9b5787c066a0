// Scripted viewer interaction (bounce view --script FILE): one action per line, run in order;
// `wait N` lets N frames render before the next line. Blank lines and text after '#' are
// ignored. The verbs and their arguments are listed in kScriptVerbs (script.cpp) and in
// `bounce view --help`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bounce/render/denoiser.h"

namespace bounce::app {

struct ScriptAction {
  std::string file;
  int line = 0;
  std::string verb;
  std::vector<std::string> args;

  // "actions.txt:3" for messages.
  std::string where() const { return file + ":" + std::to_string(line); }
  float number(size_t i) const;  // args[i] as a finite number (throws Error naming the line)
  int integer(size_t i) const;
  bool on_off(size_t i) const;  // on/off/true/false/1/0
};

// Reads and checks a script: unknown verbs and wrong argument counts are errors naming the file
// and line.
std::vector<ScriptAction> load_script(const std::string& path);
// The denoiser's debug views by name ("denoised", "raw", ...), for scripts and the panel.
const std::vector<std::pair<DenoiseView, std::string>>& denoise_view_names();
// The view a name stands for; fails naming `where` for an unknown one.
DenoiseView parse_denoise_view(const std::string& name, const std::string& where);
// The verbs with their argument synopsis, for help text.
std::string script_help();

}  // namespace bounce::app
