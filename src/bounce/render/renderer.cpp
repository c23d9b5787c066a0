#include "bounce/render/renderer.h"

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/qmc.h"
#include "bounce/core/tonemap.h"
#include "bounce/render/direct.h"

namespace bounce {

Renderer::Renderer(const Scene& scene, Tracer& tracer, std::unique_ptr<Technique> technique)
    : scene_(scene), tracer_(tracer), technique_(std::move(technique)) {
  technique_->scene_changed(scene_, tracer_);
}

void Renderer::set_technique(std::unique_ptr<Technique> technique) {
  technique_ = std::move(technique);
  technique_->scene_changed(scene_, tracer_);
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

void Renderer::update_scene() {
  if (!pending_.any()) return;
  // Sphere lights are trace geometry: a light change updates the tracer too.
  if (pending_.geometry() || pending_.lights) tracer_.update(scene_, pending_.moved_meshes);
  technique_->scene_changed(scene_, tracer_);
  direct_frames_ = 0;
  pending_ = SceneChange{};
}

void Renderer::average_direct(const CameraRays& rays, const FrameSettings& settings) {
  Image& direct = frame_.direct;
  const bool same = rays == last_rays_ && settings.light_samples == last_light_samples_;
  last_rays_ = rays;
  last_light_samples_ = settings.light_samples;
  if (!settings.accumulate || !same || direct_frames_ == 0) {
    direct_frames_ = settings.accumulate ? 1 : 0;
    if (settings.accumulate) direct_sum_ = direct;
    frame_.direct_frames = 1;
    return;
  }
  ++direct_frames_;
  const float inv = 1.0f / float(direct_frames_);
  parallel_for(
      direct.pixel_count(),
      [&](size_t i) {
        vec3& sum = direct_sum_.pixels()[i];
        sum += direct.pixels()[i];
        direct.pixels()[i] = sum * inv;
      },
      4096);
  frame_.direct_frames = direct_frames_;
}

const Frame& Renderer::render(const Camera& camera, const FrameSettings& settings) {
  if (settings.width <= 0 || settings.height <= 0)
    fail("image size {}x{} is not positive", settings.width, settings.height);
  if (settings.light_samples <= 0)
    fail("light samples must be positive (got {})", settings.light_samples);
  Frame& f = frame_;
  f.times.clear();
  {
    ScopedStage stage(f.times, "scene");
    update_scene();
  }
  f.times.add("scene", pose_ms_);
  pose_ms_ = 0.0;
  const int w = settings.width, h = settings.height;
  const CameraRays rays = CameraRays::from(camera, w, h);
  // Jittered frames walk a Halton (2, 3) pattern over the pixel, so their average is the
  // pixel's box-filtered value; unjittered frames sample pixel centres.
  const vec2 subpixel =
      settings.jitter ? vec2(halton(0, frame_index_ + 1), halton(1, frame_index_ + 1)) : vec2(0.5f);
  {
    ScopedStage stage(f.times, "gbuffer");
    if (f.gbuffer.width != w || f.gbuffer.height != h) f.gbuffer.resize(w, h);
    f.primary_rays = build_gbuffer(scene_, tracer_, rays, subpixel, f.gbuffer);
  }
  {
    ScopedStage stage(f.times, "direct");
    if (f.direct.width() != w || f.direct.height() != h) f.direct = Image(w, h);
    const DirectSettings direct{settings.light_samples, frame_index_, settings.seed};
    f.shadow_rays = compute_direct(scene_, tracer_, f.gbuffer, rays.origin, direct, f.direct);
    average_direct(rays, settings);
  }
  const bool indirect = technique_->has_indirect();
  if (indirect) {
    ScopedStage stage(f.times, "indirect");
    f.indirect = Image(w, h);
    f.technique = TechniqueCounters{};
    FrameContext context{scene_, tracer_, f.gbuffer, rays, frame_index_, f.times, f.technique};
    technique_->indirect(context, f.indirect);
  } else {
    f.indirect = Image();
    f.technique = TechniqueCounters{};
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
  {
    ScopedStage stage(f.times, "tonemap");
    tonemap_srgb8(f.color, settings.exposure_ev, f.ldr);
  }
  ++frame_index_;
  return f;
}

Image render_image(const Scene& scene, const std::string& technique, const FrameSettings& settings,
                   int spp) {
  if (spp <= 0) fail("samples per pixel must be positive (got {})", spp);
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique(technique));
  FrameSettings s = settings;
  s.jitter = spp > 1;
  Image sum(s.width, s.height);
  for (int k = 0; k < spp; ++k) sum += renderer.render(scene.camera, s).color;
  return sum * (1.0f / float(spp));
}

}  // namespace bounce
