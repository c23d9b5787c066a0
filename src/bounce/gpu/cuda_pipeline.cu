#include "bounce/gpu/cuda_pipeline.h"

#include <string>
#include <vector>

#include "bounce/core/color.h"
#include "bounce/gpu/cuda_device.h"
#include "bounce/gpu/device_denoiser.h"
#include "bounce/gpu/device_gbuffer.h"
#include "bounce/gpu/device_scene.h"
#include "bounce/gpu/device_tiled.h"
#include "bounce/gpu/launch.h"
#include "bounce/render/denoiser.h"
#include "bounce/render/direct_kernel.h"
#include "bounce/render/gbuffer_kernel.h"
#include "bounce/render/motion_kernel.h"
#include "bounce/render/renderer.h"

namespace bounce {

// Stage times from CUDA events: each stage is bracketed by two events on the stream, and the
// times are read once the frame is done, so timing adds no waits between stages.
class StageEvents {
 public:
  ~StageEvents() {
    for (Mark& m : marks_) {
      cudaEventDestroy(m.begin);
      cudaEventDestroy(m.end);
    }
  }
  void begin(const std::string& name) {
    if (used_ == marks_.size()) {
      Mark m;
      BOUNCE_CUDA(cudaEventCreate(&m.begin));
      BOUNCE_CUDA(cudaEventCreate(&m.end));
      marks_.push_back(m);
    }
    marks_[used_].name = name;
    BOUNCE_CUDA(cudaEventRecord(marks_[used_].begin));
  }
  void end() { BOUNCE_CUDA(cudaEventRecord(marks_[used_++].end)); }
  // Waits for the last stage and adds every stage's time to `times`.
  void collect(StageTimes& times) {
    if (used_ == 0) return;
    BOUNCE_CUDA(cudaEventSynchronize(marks_[used_ - 1].end));
    for (size_t k = 0; k < used_; ++k) {
      float ms = 0.0f;
      BOUNCE_CUDA(cudaEventElapsedTime(&ms, marks_[k].begin, marks_[k].end));
      times.add(marks_[k].name, ms);
    }
    used_ = 0;
  }

 private:
  struct Mark {
    std::string name;
    cudaEvent_t begin = nullptr, end = nullptr;
  };
  std::vector<Mark> marks_;
  size_t used_ = 0;
};

class CudaPipeline final : public DevicePipeline {
 public:
  std::string name() const override { return "cuda (" + cuda_device_info().name + ")"; }
  void render(const DeviceFrameInput& in, Frame& f) override;

 private:
  DeviceScene scene_;
  DeviceGBuffer g_;
  DeviceTiled tiled_;
  DeviceDenoiser denoiser_;
  DeviceBuffer<vec3> direct_, indirect_, color_, direct_sum_;
  DeviceBuffer<uint32_t> shadow_rays_;
  DeviceBuffer<uint8_t> ldr_;
  DeviceScratch scratch_;
  StageEvents events_;
};

// Averages `image` with the frames since the last change while at rest (the Renderer's
// RunningAverage, on the device).
void average_at_rest(DeviceBuffer<vec3>& image, DeviceBuffer<vec3>& sum, bool rest, int frames) {
  const size_t n = image.size();
  sum.resize(n);
  vec3* s = sum.data();
  vec3* px = image.data();
  const bool first = !rest || frames <= 1;
  const float inv = 1.0f / float(first ? 1 : frames);
  launch(n, [=] __device__(uint32_t i) {
    const vec3 total = first ? px[i] : s[i] + px[i];
    s[i] = total;
    px[i] = total * inv;
  });
}

void CudaPipeline::render(const DeviceFrameInput& in, Frame& f) {
  const std::string technique = in.technique.name();
  auto* tiled = dynamic_cast<TiledPhotonMapping*>(&in.technique);
  if (technique != "direct" && !tiled)
    gpu_fail("--device cuda: technique '" + technique +
             "' does not run on the GPU yet (direct and tiled do)");
  // The device's BVH copy carries no cut-out data (trace/cutout_view.h): refuse rather than
  // render masked holes as solid.
  for (const Material& m : in.scene.materials)
    if (m.has_cutouts())
      gpu_fail("--device cuda: material '" + m.name +
               "' has alpha cut-outs (glTF alphaMode MASK or BLEND), which the GPU does not "
               "trace yet; render this scene with --device cpu");
  const FrameSettings& settings = in.settings;
  const int w = settings.width, h = settings.height;
  const size_t n = size_t(w) * size_t(h);
  f.technique = TechniqueCounters{};
  // The denoiser's temporal part takes over the averaging at rest (as in Renderer::render).
  const bool denoise = settings.denoise;
  const bool average = !(denoise && in.denoiser.settings().temporal);

  events_.begin("scene upload");
  scene_.update(in.scene, in.scene_data, in.lights, in.change);
  events_.end();
  const SceneView sv = scene_.view();
  const TraceView tv = scene_.trace();

  events_.begin("prepare");
  if (tiled)
    tiled_.prepare(tiled->settings(), scene_, in.change, settings.accumulate, in.frame_index,
                   f.technique);
  events_.end();

  events_.begin("gbuffer");
  if (g_.width != w || g_.height != h) g_.resize(w, h);
  const GBufferView g = g_.view();
  const CameraRays rays = in.rays, previous = in.previous_rays;
  const vec2 subpixel = in.subpixel;
  launch_2d(w, h, [=] __device__(int x, int y) {
    Ray ray;
    ray.origin = rays.origin;
    ray.direction = rays.direction(float(x) + subpixel.x, float(y) + subpixel.y);
    ray.tmin = 0.0f;
    gbuffer_pixel(sv, rays.forward, rays.pixel_spread(), ray, tv.intersect(ray), g.index(x, y), g);
  });
  launch(n, [=] __device__(uint32_t i) { g.motion[i] = motion_pixel(sv, rays, previous, g, i); });
  events_.end();
  f.primary_rays = n;

  events_.begin("direct");
  direct_.resize(n);
  shadow_rays_.resize(n);
  {
    const ConstGBufferView read = g;
    const LightPickerView lights = scene_.lights();
    const DirectSettings ds = direct_settings(settings, in.frame_index);
    vec3* out = direct_.data();
    uint32_t* counts = shadow_rays_.data();
    const vec3 eye = rays.origin;
    launch(n, [=] __device__(uint32_t i) {
      vec3 sum = read.emission[i];
      uint32_t traced = 0;
      auto shadow = [&](const Ray& ray, vec3 radiance) {
        ++traced;
        if (!tv.occluded(ray)) sum += radiance;
      };
      direct_light_pixel(sv, lights, read, i, eye, ds, shadow);
      out[i] = sum;
      counts[i] = traced;
    });
    if (average) average_at_rest(direct_, direct_sum_, in.rest, f.frames_averaged);
  }
  events_.end();

  const bool indirect = tiled != nullptr;
  if (indirect) {
    events_.begin("indirect");
    indirect_.resize(n);
    tiled_.indirect(scene_, g, rays, indirect_.data());
    events_.end();
  }

  if (denoise) {
    // Debug views (FrameSettings::view) are the CPU's only: the GPU shows the denoised image.
    events_.begin("denoise");
    denoiser_.run(
        in.denoiser.settings(),
        DeviceDenoiseFrame{g, in.history, in.technique.indirect_history(), in.direct_region},
        direct_.data(), indirect ? indirect_.data() : nullptr);
    events_.end();
  }

  events_.begin("composite");
  color_.resize(n);
  {
    vec3* color = color_.data();
    const vec3* d = direct_.data();
    const vec3* ind = indirect ? indirect_.data() : nullptr;
    launch(n, [=] __device__(uint32_t i) { color[i] = ind ? d[i] + ind[i] : d[i]; });
  }
  events_.end();

  events_.begin("tonemap");
  ldr_.resize(3 * n);
  {
    const float scale = std::exp2(settings.exposure_ev);
    const vec3* color = color_.data();
    uint8_t* ldr = ldr_.data();
    launch(n, [=] __device__(uint32_t i) {
      for (int k = 0; k < 3; ++k) ldr[3 * i + k] = srgb8_from_linear(color[i][k], scale);
    });
  }
  events_.end();

  // The image back to the host: the one transfer of every frame, the linear colour only when
  // asked (four times the bytes of the tone-mapped image).
  events_.begin("download");
  if (settings.host_color) {
    if (f.color.width() != w || f.color.height() != h) f.color = Image(w, h);
    color_.download(f.color.pixels().data(), n);
  } else {
    f.color = Image();
  }
  f.width = w;
  f.height = h;
  f.ldr.resize(3 * n);
  ldr_.download(f.ldr.data(), 3 * n);
  events_.end();
  events_.collect(f.times);
  f.shadow_rays = device_sum(shadow_rays_.data(), n, scratch_);
  f.gbuffer = GBuffer{};
  f.direct = Image();
  f.indirect = Image();
}

std::unique_ptr<DevicePipeline> make_cuda_pipeline() {
  require_cuda_device("--device cuda");
  return std::make_unique<CudaPipeline>();
}

}  // namespace bounce
