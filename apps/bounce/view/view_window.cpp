#include "view_window.h"

// epoxy before GLFW, and GLFW without its own GL header.
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "bounce/core/error.h"
#include "bounce/core/image_io.h"
#include "gl_display.h"
#include "ui_panel.h"

namespace bounce::app {

namespace {

constexpr double kScriptedStep = 1.0 / 30.0;  // animation seconds per frame in scripted runs
constexpr float kLookDegreesPerPixel = 0.15f;

std::string glfw_error_text() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? text : "unknown error";
}

// Owns GLFW, the window and ImGui; tears them down in the right order.
class Window {
 public:
  Window(int width, int height, const std::string& title) {
    if (!glfwInit())
      fail(
          "viewer: cannot start GLFW ({}); a display is needed: set DISPLAY, or run headless "
          "under xvfb-run",
          glfw_error_text());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
      const std::string why = glfw_error_text();
      glfwTerminate();
      fail("viewer: cannot open an OpenGL 3.3 core window ({})", why);
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(0);  // the engine's frame time, not the display's, paces the loop
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~Window() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* get() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

void save_screenshot(const std::string& path, int width, int height) {
  const std::vector<uint8_t> rgb = GlDisplay::read_back(width, height);
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  save_png_rgb8(path, width, height, rgb.data());
  fmt::print("wrote {}\n", path);
}

// Keyboard and mouse to camera moves and toggles; ImGui gets the input it is using.
void handle_input(GLFWwindow* window, ViewSession& session, PanelState& panel, bool& show_ui,
                  double dt) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) {
    const auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
    vec3 move(0.0f);
    if (down(GLFW_KEY_W)) move.z += 1.0f;
    if (down(GLFW_KEY_S)) move.z -= 1.0f;
    if (down(GLFW_KEY_D)) move.x += 1.0f;
    if (down(GLFW_KEY_A)) move.x -= 1.0f;
    if (down(GLFW_KEY_E)) move.y += 1.0f;
    if (down(GLFW_KEY_Q)) move.y -= 1.0f;
    const float boost = down(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f;
    if (move != vec3(0.0f)) {
      session.follow_path() = false;
      session.camera().move(glm::normalize(move) * panel.move_speed * boost * float(dt));
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) session.set_flashlight(!session.flashlight());
    if (ImGui::IsKeyPressed(GLFW_KEY_P, false) || ImGui::IsKeyPressed(GLFW_KEY_F12, false))
      panel.screenshot_requested = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false)) show_ui = !show_ui;
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) session.playing() = !session.playing();
    if (ImGui::IsKeyPressed(GLFW_KEY_C, false)) session.follow_path() = !session.follow_path();
    // N: the raw frame against the denoised one; V: every view in turn.
    if (ImGui::IsKeyPressed(GLFW_KEY_N, false))
      session.view() =
          session.view() == DenoiseView::kRaw ? DenoiseView::kDenoised : DenoiseView::kRaw;
    if (ImGui::IsKeyPressed(GLFW_KEY_V, false)) {
      const auto& views = denoise_view_names();
      size_t next = 0;
      for (size_t k = 0; k < views.size(); ++k)
        if (views[k].first == session.view()) next = (k + 1) % views.size();
      session.view() = views[next].first;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) glfwSetWindowShouldClose(window, GLFW_TRUE);
  }
  if (!io.WantCaptureMouse) {
    const bool look =
        ImGui::IsMouseDown(ImGuiMouseButton_Left) || ImGui::IsMouseDown(ImGuiMouseButton_Right);
    if (look && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
      session.follow_path() = false;
      session.camera().turn(io.MouseDelta.x * kLookDegreesPerPixel,
                            -io.MouseDelta.y * kLookDegreesPerPixel);
    }
    if (io.MouseWheel != 0.0f)
      panel.move_speed =
          std::clamp(panel.move_speed * std::pow(1.25f, io.MouseWheel), 0.01f, 100.0f);
  }
}

std::string default_screenshot_name(const ViewOptions& o, int n) {
  return fmt::format("bounce-{}-{}.png", scene_stem(o.frame.scene), n);
}

}  // namespace

void run_viewer(const ViewOptions& options) {
  const std::vector<ScriptAction> script =
      options.script.empty() ? std::vector<ScriptAction>{} : load_script(options.script);
  ViewSession session(options);
  Window window(options.frame.width, options.frame.height,
                fmt::format("bounce view: {}", session.scene().source));
  GlDisplay display;
  PanelState panel;
  panel.move_speed = std::max(0.05f, 0.1f * session.scene().bounds.diagonal());
  bool show_ui = !options.hide_ui;
  const bool scripted = !script.empty() || options.frames > 0;

  size_t next_action = 0;
  int wait_frames = 0;
  int screenshots = 0;
  bool quit = false;
  auto last = std::chrono::steady_clock::now();
  while (!glfwWindowShouldClose(window.get()) && !quit) {
    glfwPollEvents();
    const auto now = std::chrono::steady_clock::now();
    const double real_dt = std::chrono::duration<double>(now - last).count();
    last = now;
    const double dt = scripted ? kScriptedStep : std::min(real_dt, 0.25);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_input(window.get(), session, panel, show_ui, real_dt);

    // Script: run actions up to the next wait; screenshots are taken after this frame draws.
    std::vector<std::string> shots;
    while (wait_frames == 0 && next_action < script.size()) {
      const ScriptAction& a = script[next_action++];
      if (session.apply(a)) continue;
      if (a.verb == "wait")
        wait_frames = a.integer(0);
      else if (a.verb == "ui")
        show_ui = a.on_off(0);
      else if (a.verb == "screenshot")
        shots.push_back(a.args[0]);
      else if (a.verb == "quit")
        quit = true;
      if (!shots.empty() || quit) break;  // draw the frame the screenshot or quit refers to
    }
    if (wait_frames > 0) --wait_frames;

    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window.get(), &fb_w, &fb_h);
    if (fb_w > 0 && fb_h > 0) {
      const Frame& f = session.render(fb_w, fb_h, dt);
      display.upload(f.ldr.data(), f.width, f.height);
      display.draw(fb_w, fb_h);
      if (show_ui) draw_panel(session, panel);
    }
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if (panel.screenshot_requested) {
      shots.push_back(default_screenshot_name(options, ++screenshots));
      panel.screenshot_requested = false;
    }
    const bool frames_done =
        options.frames > 0 && session.frames_rendered() >= uint64_t(options.frames);
    const bool script_done = !script.empty() && next_action >= script.size() && wait_frames == 0;
    const bool last_frame = frames_done || script_done || quit;
    if (last_frame && !options.screenshot.empty()) shots.push_back(options.screenshot);
    for (const auto& path : shots) save_screenshot(path, fb_w, fb_h);
    glfwSwapBuffers(window.get());
    if (last_frame) break;
  }
  const Frame& f = session.frame();
  fmt::print("{} frames; last frame {:.1f} ms at {}x{}\n", session.frames_rendered(),
             f.times.total_ms(), f.width, f.height);
}

}  // namespace bounce::app
