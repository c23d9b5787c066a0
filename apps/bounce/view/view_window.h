// The viewer's window: GLFW + OpenGL 3.3 core + Dear ImGui around a ViewSession. Turns keys,
// mouse and script actions into session controls, shows frames, takes screenshots.
#pragma once

#include "view_session.h"

namespace bounce::app {

// Opens the window and runs until it is closed, `--frames` frames are done or the script ends.
void run_viewer(const ViewOptions& options);

}  // namespace bounce::app
