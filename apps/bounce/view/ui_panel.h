// The viewer's Dear ImGui panel: technique and its parameters, per-stage timings and a
// frame-time graph, camera, animation, lights (position, colour, intensity), flashlight,
// exposure and the resolution scaler.
#pragma once

#include "view_session.h"

namespace bounce::app {

struct PanelState {
  float move_speed = 1.0f;  // metres per second (scroll wheel)
  bool screenshot_requested = false;
};

void draw_panel(ViewSession& session, PanelState& state);

}  // namespace bounce::app
