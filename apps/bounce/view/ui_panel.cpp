#include "ui_panel.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <iterator>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/render/technique.h"
#include "bounce/techniques/registry.h"

namespace bounce::app {

namespace {

// Parameters, each as the widget its kind calls for. Widgets write the values in place; the
// Renderer compares the technique's parameters each frame and reports a change to the technique
// (and to the resolution scaler, as motion); the denoiser's apply from the next frame.
void param_widgets(const ParamSet& params) {
  for (const Param& p : params.all()) {
    switch (p.kind) {
      case Param::Kind::kBool:
        ImGui::Checkbox(p.name.c_str(), static_cast<bool*>(p.value));
        break;
      case Param::Kind::kInt: {
        int* v = static_cast<int*>(p.value);
        int edited = *v;
        if (p.max - p.min <= 64)
          ImGui::SliderInt(p.name.c_str(), &edited, int(p.min), int(p.max));
        else
          ImGui::InputInt(p.name.c_str(), &edited, 1, 100);
        *v = std::clamp(edited, int(p.min), int(p.max));
        break;
      }
      case Param::Kind::kFloat: {
        float* v = static_cast<float*>(p.value);
        float edited = *v;
        ImGui::DragFloat(p.name.c_str(), &edited, std::max(1e-4f, 0.01f * std::abs(*v)),
                         float(p.min), float(p.max), "%.4g");
        *v = std::clamp(edited, float(p.min), float(p.max));
        break;
      }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.help.c_str());
  }
}

void technique_section(ViewSession& session) {
  const std::vector<std::string> names = technique_names();
  const std::string current = session.technique_name();
  if (ImGui::BeginCombo("technique", current.c_str())) {
    for (const auto& name : names)
      if (ImGui::Selectable(name.c_str(), name == current)) session.set_technique(name);
    ImGui::EndCombo();
  }
  param_widgets(session.technique().params());
}

// Temporal reuse and denoising: on or off, what to show, and the filter's parameters.
void denoiser_section(ViewSession& session) {
  ImGui::Checkbox("denoise", &session.denoise());
  std::string shown;
  for (const auto& [view, name] : denoise_view_names())
    if (view == session.view()) shown = name;
  if (ImGui::BeginCombo("show (N, V)", shown.c_str())) {
    for (const auto& [view, name] : denoise_view_names())
      if (ImGui::Selectable(name.c_str(), view == session.view())) session.view() = view;
    ImGui::EndCombo();
  }
  if (session.denoise()) param_widgets(session.denoiser().params());
}

void timing_section(const ViewSession& session) {
  const Frame& f = session.frame();
  const auto& history = session.frame_ms_history();
  std::vector<float> values(history.begin(), history.end());
  float peak = 1.0f;
  for (float v : values) peak = std::max(peak, v);
  const std::string overlay = fmt::format("{:.1f} ms", f.times.total_ms());
  ImGui::PlotLines("##frame", values.data(), int(values.size()), 0, overlay.c_str(), 0.0f,
                   peak * 1.1f, ImVec2(ImGui::GetContentRegionAvail().x, 60.0f));
  if (ImGui::BeginTable("stages", 2, ImGuiTableFlags_RowBg)) {
    for (const StageTime& s : f.times.stages()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(s.name.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%7.2f ms", s.ms);
    }
    ImGui::EndTable();
  }
}

// Colour and strength of a light's emission edited separately: strength is the largest
// channel, colour the emission divided by it.
bool colour_and_strength(const char* id, vec3& emission) {
  const float strength = max_component(emission);
  vec3 colour = strength > 0.0f ? emission / strength : vec3(1.0f);
  float s = strength;
  bool changed = ImGui::ColorEdit3(fmt::format("colour##{}", id).c_str(), &colour.x);
  changed |= ImGui::DragFloat(fmt::format("strength##{}", id).c_str(), &s,
                              std::max(0.01f, 0.01f * s), 0.0f, 1e6f, "%.3g");
  if (changed) emission = glm::max(colour, vec3(0.0f)) * std::max(s, 0.0f);
  return changed;
}

void lights_section(ViewSession& session) {
  Scene& scene = session.scene();
  const float step = 0.005f * std::max(scene.bounds.diagonal(), 1e-3f);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    Light& l = scene.lights[i];
    const std::string id = fmt::format("light{}", i);
    ImGui::PushID(id.c_str());
    ImGui::Text("%s (%s)", l.name.c_str(), l.type_name());
    bool changed = false;
    if (l.type != LightType::kDirectional && l.type != LightType::kEnvironment)
      changed |= ImGui::DragFloat3("position", &l.position.x, step);
    changed |= colour_and_strength(id.c_str(), l.emission());
    if (l.type == LightType::kEnvironment) {
      float degrees = glm::degrees(l.rotation);
      if (ImGui::SliderFloat("rotation (deg)", &degrees, -180.0f, 180.0f, "%.1f")) {
        l.rotation = glm::radians(degrees);
        changed = true;
      }
    }
    if (changed) session.lights_changed();
    ImGui::PopID();
  }
  for (size_t i = 0; i < scene.area_lights.size(); ++i) {
    const AreaLight& al = scene.area_lights[i];
    const TriangleRef first = al.triangles.front();
    const uint32_t material = scene.meshes[first.mesh].materials[first.triangle];
    ImGui::PushID(int(1000000 + i));
    ImGui::Text("%s (area, %.3g m^2)", al.name.c_str(), al.area);
    Material& m = scene.materials[material];
    if (colour_and_strength("area", m.emission)) session.materials_changed();
    vec3 offset(0.0f);
    if (ImGui::DragFloat3("move", &offset.x, step) && offset != vec3(0.0f))
      session.move_area_light(i, offset);
    ImGui::PopID();
  }
}

// Meshes to move by hand (the first kMaxListed: levels have thousands).
void objects_section(ViewSession& session) {
  constexpr size_t kMaxListed = 64;
  Scene& scene = session.scene();
  const float step = 0.005f * std::max(scene.bounds.diagonal(), 1e-3f);
  const size_t n = std::min(scene.meshes.size(), kMaxListed);
  for (size_t i = 0; i < n; ++i) {
    ImGui::PushID(int(2000000 + i));
    vec3 offset(0.0f);
    const std::string label =
        fmt::format("{} ({} tri)", scene.meshes[i].name, scene.meshes[i].triangle_count());
    if (ImGui::DragFloat3(label.c_str(), &offset.x, step) && offset != vec3(0.0f))
      session.move_mesh(uint32_t(i), offset);
    ImGui::PopID();
  }
  if (scene.meshes.size() > n) ImGui::Text("(%zu more meshes)", scene.meshes.size() - n);
}

}  // namespace

void draw_panel(ViewSession& session, PanelState& state) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("bounce");
  const Frame& f = session.frame();
  const Scene& scene = session.scene();
  ImGui::Text("%s: %zu triangles", scene.source.c_str(), scene.triangle_count());
  ImGui::Text("%dx%d internal, %s", f.width, f.height, session.moving() ? "moving" : "at rest");
  ImGui::Text("%d frame(s) averaged at rest", f.frames_averaged);

  if (ImGui::CollapsingHeader("timings", ImGuiTreeNodeFlags_DefaultOpen)) timing_section(session);
  if (ImGui::CollapsingHeader("technique", ImGuiTreeNodeFlags_DefaultOpen)) {
    try {
      technique_section(session);
    } catch (const Error& e) {
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", e.what());
    }
  }
  if (ImGui::CollapsingHeader("denoiser", ImGuiTreeNodeFlags_DefaultOpen))
    denoiser_section(session);
  if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::SliderFloat("exposure", &session.exposure(), -8.0f, 8.0f, "%.1f EV");
    constexpr int kChoices = int(std::size(kShadowRayChoices));
    int shadow_rays = 0;
    for (int k = 0; k < kChoices; ++k)
      if (session.shadow_rays() == kShadowRayChoices[k]) shadow_rays = k;
    if (ImGui::Combo("shadow rays", &shadow_rays, kShadowRayChoices, kChoices))
      session.shadow_rays() = kShadowRayChoices[shadow_rays];
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "all: one per light sample; one: one per pixel, for the light sample chosen by its "
          "unshadowed light; auto: one with one light sample");
    bool apart = !session.moving_lights_in_history();
    if (ImGui::Checkbox("moving lights apart", &apart)) session.moving_lights_in_history() = !apart;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "A moving flashlight or lamp shaded with a shadow ray of its own and kept out of the "
          "denoiser's history, so its light shows where it is; off: averaged with the rest");
    float target = float(session.scaler().settings().target_ms);
    if (ImGui::SliderFloat("target ms", &target, 0.0f, 200.0f, "%.0f"))
      session.scaler().settings().target_ms = target;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("In motion the internal resolution follows this frame time (0: off)");
    bool flash = session.flashlight();
    if (ImGui::Checkbox("flashlight (F)", &flash)) session.set_flashlight(flash);
    if (session.flashlight()) {
      FlashlightSettings& fs = session.flashlight_settings();
      bool changed = colour_and_strength("flashlight", fs.intensity);
      changed |= ImGui::SliderFloat("cone", &fs.outer_deg, 2.0f, 89.0f, "%.0f deg");
      fs.inner_deg = std::min(fs.inner_deg, 0.5f * fs.outer_deg);
      if (changed) session.flashlight_edited();
    }
    const vec3 p = session.camera().position();
    ImGui::Text("camera (%.2f, %.2f, %.2f) yaw %.0f pitch %.0f", p.x, p.y, p.z,
                session.camera().yaw_deg(), session.camera().pitch_deg());
    ImGui::DragFloat("speed (wheel)", &state.move_speed, 0.01f, 0.01f, 100.0f, "%.2f m/s");
    if (ImGui::Button("reset camera")) session.reset_camera();
    ImGui::SameLine();
    if (ImGui::Button("screenshot (P)")) state.screenshot_requested = true;
  }
  if (!scene.animation.empty() || !scene.animation.camera_path.empty()) {
    if (ImGui::CollapsingHeader("animation", ImGuiTreeNodeFlags_DefaultOpen)) {
      ImGui::Checkbox("play (space)", &session.playing());
      float t = session.time();
      if (ImGui::SliderFloat("time", &t, 0.0f, std::max(scene.animation.duration(), 0.01f),
                             "%.2f s"))
        session.set_time(t);
      if (!scene.animation.camera_path.empty())
        ImGui::Checkbox("follow camera path (C)", &session.follow_path());
    }
  }
  if (ImGui::CollapsingHeader("lights")) lights_section(session);
  if (ImGui::CollapsingHeader("objects (drag to move)")) objects_section(session);
  ImGui::End();
}

}  // namespace bounce::app
