#include "bounce/render/renderer.h"

#include <algorithm>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/core/tonemap.h"
#include "bounce/render/direct.h"
#include "bounce/render/gbuffer_direct.h"

namespace bounce {

Renderer::Renderer(const Scene& scene, Tracer& tracer, std::unique_ptr<Technique> technique)
    : scene_(scene), tracer_(tracer), technique_(std::move(technique)) {}

void Renderer::set_technique(std::unique_ptr<Technique> technique) {
  technique_ = std::move(technique);
  pending_.merge(SceneChange::all());
}

void Renderer::set_device(std::unique_ptr<DevicePipeline> device) {
  device_ = std::move(device);
  pending_.merge(SceneChange::all());
}

void Renderer::scene_changed(const SceneChange& change) {
  pending_.merge(change);
}

void Renderer::animate(Scene& scene, float t) {
  if (&scene != &scene_) fail("{}: Renderer::animate was given another scene", scene.source);
  Stopwatch watch;
  scene_changed(bounce::animate(scene, t));
  pose_ms_ += watch.elapsed_ms();
}

std::vector<std::string> Renderer::parameter_state(const FrameSettings& settings) const {
  std::vector<std::string> state;
  for (const Param& p : technique_->params().all()) state.push_back(p.to_string());
  state.push_back(std::to_string(settings.light_samples));
  state.push_back(settings.one_shadow_ray ? "one shadow ray" : "a ray per sample");
  state.push_back(std::to_string(settings.seed));
  state.push_back(settings.accumulate ? "accumulate" : "per-frame");
  state.push_back(settings.denoise ? "denoise" : "raw");
  state.push_back(settings.moving_lights_apart ? "moving lights apart"
                                               : "moving lights in history");
  return state;
}

SceneChange Renderer::change_since_last(const Camera& camera, const FrameSettings& settings,
                                        const std::vector<std::string>& parameters,
                                        bool ignore_size) const {
  SceneChange change = pending_;
  const bool resized =
      !ignore_size && (settings.width != last_width_ || settings.height != last_height_);
  change.camera |= resized || !(camera == last_camera_);
  change.parameters |= parameters != last_parameters_;
  return change;
}

SceneChange Renderer::next_change(const Camera& camera, const FrameSettings& settings,
                                  bool ignore_size) const {
  return change_since_last(camera, settings, parameter_state(settings), ignore_size);
}

HistoryState Renderer::history_state(const SceneChange& change,
                                     const FrameSettings& settings) const {
  // History survives what moves surfaces (reprojection follows them, across a change of size
  // too: a resize counts as a camera change) but not what changes what the image means: a new
  // technique, parameters (switching the denoiser on is one), or the denoiser's own settings.
  if (!settings.accumulate || change.everything || change.parameters ||
      !(denoiser_.settings() == last_denoise_))
    return HistoryState::kReset;
  if (!change.any()) return HistoryState::kRest;
  if (change.camera_only()) return HistoryState::kCameraMoved;
  return HistoryState::kWorldChanged;
}

void Renderer::RunningAverage::add(Image& image, bool accumulate, bool rest) {
  if (!rest || frames == 0) {
    frames = 1;
    if (accumulate) sum = image;  // the first frame of a new average; nothing to keep otherwise
    return;
  }
  ++frames;
  const float inv = 1.0f / float(frames);
  parallel_for(
      image.pixel_count(),
      [&](size_t i) {
        vec3& s = sum.pixels()[i];
        s += image.pixels()[i];
        image.pixels()[i] = s * inv;
      },
      4096);
}

const Frame& Renderer::render(const Camera& camera, const FrameSettings& settings) {
  if (settings.width <= 0 || settings.height <= 0)
    fail("image size {}x{} is not positive", settings.width, settings.height);
  if (settings.light_samples <= 0)
    fail("light samples must be positive (got {})", settings.light_samples);
  Frame& f = frame_;
  f.times.clear();
  std::vector<std::string> parameters = parameter_state(settings);
  f.change = change_since_last(camera, settings, parameters, false);
  // The lights set apart this frame (moved point, spot and directional lights), and the lights as
  // the denoiser's history holds them (those set apart dark). A light that stops moving goes back
  // into a history that lacks its light: for the denoiser that is a change of lights (its cone is
  // clipped, light_change_region), though the scene's lights did not change.
  std::vector<LightRecord> lights(scene_.lights.begin(), scene_.lights.end());
  const bool keeps_history = settings.denoise && denoiser_.settings().temporal;
  const LightsApart apart =
      settings.moving_lights_apart && keeps_history && !device_ && !f.change.everything
          ? moved_punctual_lights(last_lights_, lights)
          : LightsApart{};
  std::vector<LightRecord> history_lights = lights_in_history(lights, apart);
  SceneChange history_change = f.change;
  history_change.lights |= history_lights != last_history_lights_ && !last_history_lights_.empty();
  const HistoryState history = history_state(history_change, settings);
  pending_ = SceneChange{};
  last_camera_ = camera;
  last_width_ = settings.width;
  last_height_ = settings.height;
  last_parameters_ = std::move(parameters);
  last_denoise_ = denoiser_.settings();
  const SceneChange& change = f.change;
  // Where the change reached the direct light the history holds, for the denoiser's clip: when
  // nothing but lights changed, only the cones of the spots that moved (a carried flashlight) or
  // went into or out of the history.
  const LightChangeRegion direct_region =
      light_change_region(history_change, last_history_lights_, history_lights);
  last_lights_ = std::move(lights);
  last_history_lights_ = std::move(history_lights);
  const bool rest = settings.accumulate && !history_change.any();
  rest_frames_ = rest ? rest_frames_ + 1 : 1;
  // The denoiser's temporal part takes over the averaging at rest.
  const bool average = !(settings.denoise && denoiser_.settings().temporal);
  {
    ScopedStage stage(f.times, "scene");
    // Sphere lights are trace geometry: a light change updates the tracer too.
    if (!change.moved_meshes.empty() || change.lights) tracer_.update(scene_, change.moved_meshes);
    if (change.everything)
      scene_data_.build(scene_);
    else if (change.geometry() || change.lights || change.materials)
      scene_data_.refresh(scene_, change.moved_meshes);
    else
      scene_data_.forget_motion();  // moved meshes of an earlier frame stand still now
    // Light powers change with lights, emissive materials and the area of moved emitters; the
    // lights set apart take no candidates from the others.
    if (change.everything || change.geometry() || change.lights || change.materials ||
        apart != picker_apart_)
      lights_ = LightPicker::build(scene_, apart.indices());
    picker_apart_ = apart;
  }
  f.times.add("scene", pose_ms_);
  pose_ms_ = 0.0;
  const int w = settings.width, h = settings.height;
  const CameraRays rays = CameraRays::from(camera, w, h);
  // Jittered frames walk a Halton (2, 3) pattern over the pixel, so their average is the
  // pixel's box-filtered value; unjittered frames sample pixel centres.
  const vec2 subpixel =
      settings.jitter ? vec2(halton(0, frame_index_ + 1), halton(1, frame_index_ + 1)) : vec2(0.5f);
  // Motion from the last frame's camera (none on the first frame), in this frame's pixels: after
  // a resize the last camera's rays are measured in the new size.
  CameraRays previous = frame_index_ == 0 || change.everything ? rays : last_rays_;
  previous.width = rays.width;
  previous.height = rays.height;
  last_rays_ = rays;
  f.frames_averaged = rest_frames_;
  if (device_) {
    // The device scene carries no environment map and its kernels no environment light yet:
    // refuse rather than render such a scene without its light.
    if (scene_data_.view().environment >= 0)
      fail(
          "{}: the scene has an environment light, which --device cuda does not render yet "
          "(render it on the CPU, or give the scene other lights)",
          scene_.source);
    device_->render(
        DeviceFrameInput{scene_, scene_data_, lights_, *technique_, settings, change, rays,
                         previous, subpixel, rest, history, direct_region, denoiser_, frame_index_},
        f);
    ++frame_index_;
    return f;
  }
  f.technique = TechniqueCounters{};
  {
    ScopedStage stage(f.times, "prepare");
    technique_->prepare(PrepareContext{scene_, scene_data_.view(), tracer_, change,
                                       settings.accumulate, frame_index_, f.times, f.technique});
  }
  const bool indirect = technique_->has_indirect();
  const FrameContext context{scene_, scene_data_.view(),  tracer_,      f.gbuffer, rays,
                             change, settings.accumulate, frame_index_, f.times,   f.technique};
  // The technique's G-buffer work done inside the pass (Technique::begin_gbuffer_bands), timed
  // as this sub-stage of "indirect".
  std::string band_stage;
  double band_ms = 0.0;
  {
    // One pass: each band's direct light right after its G-buffer, from the cache.
    if (f.gbuffer.width != w || f.gbuffer.height != h) f.gbuffer.resize(w, h);
    if (f.direct.width() != w || f.direct.height() != h) f.direct = Image(w, h);
    if (apart.count > 0 && (f.apart.width() != w || f.apart.height() != h)) f.apart = Image(w, h);
    DirectSettings direct = direct_settings(settings, frame_index_);
    static_assert(LightsApart::kMax <= DirectSettings::kMaxApart);
    direct.apart_count = apart.count;
    for (int k = 0; k < apart.count; ++k) direct.apart[k] = apart.index[k];
    if (indirect) band_stage = technique_->begin_gbuffer_bands(context);
    AfterBand after_band;
    if (!band_stage.empty())
      after_band = [this](int x0, int y0, int x1, int y1) {
        technique_->gbuffer_band(x0, y0, x1, y1);
      };
    // Primary visibility from the raster where it pays and can stand for the camera rays.
    Stopwatch raster_watch;
    const bool rastered = settings.raster_primary && raster_pays(scene_.triangle_count(), w, h) &&
                          raster_.build(scene_data_.view(), rays, subpixel, w, h);
    f.times.add("gbuffer", raster_watch.elapsed_ms());
    const GBufferAndDirect pass = build_gbuffer_and_direct(
        scene_data_.view(), lights_.view(), tracer_, rays, subpixel, direct, f.gbuffer, f.direct,
        apart.count > 0 ? &f.apart : nullptr, after_band, rastered ? &raster_ : nullptr);
    f.primary_rays = pass.primary_rays;
    f.shadow_rays = pass.shadow_rays;
    f.times.add("gbuffer", pass.gbuffer_ms);
    f.times.add("direct", pass.direct_ms);
    band_ms = pass.band_ms;
  }
  {
    ScopedStage stage(f.times, "gbuffer");
    compute_motion(scene_data_.view(), rays, previous, f.gbuffer);
  }
  if (average) {
    ScopedStage stage(f.times, "direct");
    direct_average_.add(f.direct, settings.accumulate, rest);
  }
  if (indirect) {
    if (!band_stage.empty()) f.times.add(band_stage, band_ms);
    ScopedStage stage(f.times, "indirect");
    // Reused frame to frame (a fresh 3 MB image each frame costs page faults), zeroed unless the
    // technique writes every pixel.
    if (f.indirect.width() != w || f.indirect.height() != h)
      f.indirect = Image(w, h);
    else if (!technique_->indirect_overwrites())  // on every core (11 MB at 1280 x 720)
      parallel_for(
          f.indirect.pixel_count(), [&](size_t i) { f.indirect.pixels()[i] = vec3(0.0f); }, 16384);
    technique_->indirect(context, f.indirect);
    if (average && technique_->indirect_history() != IndirectHistory::kAccumulated)
      indirect_average_.add(f.indirect, settings.accumulate, rest);
  } else {
    f.indirect = Image();
  }
  if (!band_stage.empty()) f.times.add("indirect", band_ms);  // (its sub-stage is inside it)
  if (settings.denoise) {
    ScopedStage stage(f.times, "denoise");
    denoiser_.keep_raw(settings.view == DenoiseView::kRaw);
    denoiser_.keep_motion(settings.view == DenoiseView::kMotion);
    const DenoiseFrame frame{
        f.gbuffer,           history,       technique_->indirect_history(),      f.times,
        settings.accumulate, direct_region, apart.count > 0 ? &f.apart : nullptr};
    denoiser_.run(frame, f.direct, indirect ? &f.indirect : nullptr);
  }
  {
    ScopedStage stage(f.times, "composite");
    if (f.color.width() != w || f.color.height() != h) f.color = Image(w, h);
    parallel_for(
        f.color.pixel_count(),
        [&](size_t i) {
          f.color.pixels()[i] =
              f.direct.pixels()[i] + (indirect ? f.indirect.pixels()[i] : vec3(0.0f));
        },
        4096);
  }
  if (settings.denoise && settings.view != DenoiseView::kDenoised)
    denoiser_.debug_view(settings.view, f.color);
  {
    ScopedStage stage(f.times, "tonemap");
    tonemap_srgb8(f.color, settings.exposure_ev, f.ldr);
  }
  f.width = w;
  f.height = h;
  ++frame_index_;
  return f;
}

}  // namespace bounce
