#include "view_session.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/error.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_edit.h"
#include "bounce/techniques/registry.h"

namespace bounce::app {

namespace {

constexpr size_t kHistory = 240;  // frames in the frame-time graph

vec3 vector_arg(const ScriptAction& a, size_t first) {
  return {a.number(first), a.number(first + 1), a.number(first + 2)};
}

}  // namespace

ViewSession::ViewSession(const ViewOptions& options)
    : options_(options), scene_(load_scene(options.frame.scene)) {
  scaler_.settings().target_ms = options.target_ms;
  auto technique = make_checked_technique(options.frame, scene_);
  tracer_ = make_embree_tracer(scene_);
  renderer_ = std::make_unique<Renderer>(scene_, *tracer_, std::move(technique));
  configure_pipeline(options.frame, *renderer_);
  technique_name_ = options.frame.technique;
  exposure_ = options.frame.exposure_ev;
  denoise_ = options.frame.denoise;
  camera_ = FlyCamera(scene_.camera);
  // A camera path alone is an animation to play too.
  playing_ = !scene_.animation.empty() || !scene_.animation.camera_path.empty();
  time_ = options.frame.at;
  flashlight_settings_ = app::flashlight_settings(options.frame);
  set_flashlight(options.frame.flashlight);
}

void ViewSession::reset_camera() {
  camera_ = FlyCamera(scene_.camera);
}

void ViewSession::set_technique(const std::string& name) {
  if (name == technique_name_) return;
  renderer_->set_technique(make_technique(name));  // throws Error for an unknown name
  technique_name_ = name;
}

void ViewSession::set_param(const std::string& name, const std::string& value) {
  try {
    // The technique's parameter, or else the denoiser's.
    ParamSet& technique = renderer_->technique().params();
    ParamSet& denoiser = renderer_->denoiser().params();
    if (technique.find(name) == nullptr && denoiser.find(name) != nullptr) {
      denoiser.set(name, value);
      return;
    }
    technique.set(name, value);
  } catch (const Error& e) {
    fail("technique '{}': {}", technique_name_, e.what());
  }
}

void ViewSession::lights_changed() {
  pending_.lights = true;
}

void ViewSession::materials_changed() {
  pending_.materials = true;
  pending_.lights = true;
  scene_.derive();  // emission may have turned a material into a light or back
}

void ViewSession::move_area_light(size_t index, vec3 offset) {
  pending_.merge(bounce::move_area_light(scene_, index, offset));
}

void ViewSession::move_mesh(uint32_t index, vec3 offset) {
  pending_.merge(bounce::move_mesh(scene_, index, offset));
}

void ViewSession::set_time(float t) {
  time_ = std::max(t, 0.0f);
  time_set_ = true;
}

void ViewSession::set_flashlight(bool on) {
  if (on == flashlight()) return;
  if (on) {
    flashlight_index_ = add_flashlight(scene_, camera_.camera(), flashlight_settings_);
  } else {
    scene_.lights.erase(scene_.lights.begin() + std::ptrdiff_t(*flashlight_index_));
    flashlight_index_.reset();
  }
  lights_changed();
}

void ViewSession::place_flashlight() {
  if (flashlight_index_ &&
      bounce::place_flashlight(scene_, *flashlight_index_, camera_.camera(), flashlight_settings_))
    lights_changed();
}

const Frame& ViewSession::render(int out_w, int out_h, double dt) {
  // Scene update: the animation clock, the camera path, the flashlight.
  if (playing_ && (!scene_.animation.empty() || !scene_.animation.camera_path.empty())) {
    time_ += float(dt);
    time_set_ = true;
  }
  if (time_set_) {
    renderer_->animate(scene_, time_);
    time_set_ = false;
  }
  if (follow_path_ && !scene_.animation.camera_path.empty())
    camera_ = FlyCamera(scene_.animation.camera_at(scene_.camera, time_));
  place_flashlight();
  const Camera camera = camera_.camera();

  if (pending_.any()) renderer_->scene_changed(pending_);
  pending_ = SceneChange{};

  // The Renderer tells what changed (scene edits, camera, parameters, a new technique); the
  // size is left out because the scaler chooses it from whether anything moves.
  FrameOptions frame = options_.frame;
  frame.exposure_ev = exposure_;
  frame.denoise = denoise_;
  moving_ = renderer_->next_change(camera, realtime_frame_settings(frame, true), true).any();
  FrameSettings settings = realtime_frame_settings(frame, moving_);
  settings.view = view_;
  settings.host_color = false;  // the window shows `ldr`
  const float scale = fixed_scale_ ? *fixed_scale_ : scaler_.update(last_frame_ms_, moving_);
  settings.width = std::max(1, int(std::lround(out_w * scale)));
  settings.height = std::max(1, int(std::lround(out_h * scale)));
  frame_ = &renderer_->render(camera, settings);

  last_frame_ms_ = frame_->times.total_ms();
  history_.push_back(float(last_frame_ms_));
  if (history_.size() > kHistory) history_.pop_front();
  ++frames_;
  return *frame_;
}

bool ViewSession::apply(const ScriptAction& a) {
  if (a.verb == "move") {
    camera_.move(vector_arg(a, 0));
  } else if (a.verb == "turn") {
    camera_.turn(a.number(0), a.number(1));
  } else if (a.verb == "camera") {
    Camera c = camera_.camera();
    c.position = vector_arg(a, 0);
    c.look_at = vector_arg(a, 3);
    if (glm::length(c.look_at - c.position) <= 0.0f)
      fail("{}: camera: the target equals the position", a.where());
    camera_ = FlyCamera(c);
  } else if (a.verb == "flashlight") {
    set_flashlight(a.args[0] == "toggle" ? !flashlight() : a.on_off(0));
  } else if (a.verb == "technique") {
    try {
      set_technique(a.args[0]);
    } catch (const Error& e) {
      fail("{}: {}", a.where(), e.what());
    }
  } else if (a.verb == "param") {
    try {
      set_param(a.args[0], a.args[1]);
    } catch (const Error& e) {
      fail("{}: {}", a.where(), e.what());
    }
  } else if (a.verb == "light") {
    const int i = a.integer(0);
    if (size_t(i) >= scene_.lights.size())
      fail(
          "{}: light {} does not exist (the scene has {} point, spot, directional, sphere or "
          "environment lights)",
          a.where(), i, scene_.lights.size());
    Light& l = scene_.lights[size_t(i)];
    if (a.args[1] == "rotation") {
      if (l.type != LightType::kEnvironment)
        fail("{}: light {} is a {} light; only an environment light turns", a.where(), i,
             l.type_name());
      l.rotation = glm::radians(a.number(2));
      lights_changed();
      return true;
    }
    const vec3 v = vector_arg(a, 2);
    if (a.args[1] == "position") {
      l.position = v;
    } else {
      if (glm::any(glm::lessThan(v, vec3(0.0f))))
        fail("{}: light: a colour must not be negative", a.where());
      l.emission() = v;
    }
    lights_changed();
  } else if (a.verb == "object") {
    const int i = a.integer(0);
    if (size_t(i) >= scene_.meshes.size())
      fail("{}: object {} does not exist (the scene has {} meshes)", a.where(), i,
           scene_.meshes.size());
    move_mesh(uint32_t(i), vector_arg(a, 1));
  } else if (a.verb == "denoise") {
    denoise_ = a.on_off(0);
  } else if (a.verb == "show") {
    view_ = parse_denoise_view(a.args[0], a.where());
  } else if (a.verb == "exposure") {
    exposure_ = a.number(0);
  } else if (a.verb == "play") {
    playing_ = a.on_off(0);
  } else if (a.verb == "time") {
    set_time(a.number(0));
  } else if (a.verb == "path") {
    follow_path_ = a.on_off(0);
  } else if (a.verb == "scale") {
    const float s = a.number(0);
    if (!(s > 0.0f && s <= 1.0f)) fail("{}: scale must be in (0, 1], got {}", a.where(), s);
    fixed_scale_ = s;
  } else {
    return false;
  }
  return true;
}

}  // namespace bounce::app
