// Rendering a scene in tests: frames through the pipeline with a technique set up by parameter
// name, and the offline path-traced reference to compare them with.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/render/renderer.h"
#include "bounce/techniques/path/reference.h"
#include "bounce/techniques/registry.h"

namespace bounce::render_test {

struct Job {
  Job(std::string technique_name, int image_width, int image_height)
      : technique(std::move(technique_name)), width(image_width), height(image_height) {}

  std::string technique;
  std::vector<std::pair<std::string, std::string>> params;  // technique parameters by name
  int width, height;
  int light_samples = 4;
  int frames = 1;
  bool jitter = false;  // sub-pixel jitter: the frames' average is the box-filtered pixel
  // Frames at rest average in the pipeline (FrameSettings::accumulate); off, each frame stands
  // alone and the images are the last frame's.
  bool accumulate = true;
  bool denoise = false;  // the denoiser stage with its defaults (FrameSettings::denoise)
  uint32_t seed = 0;
  int threads = 0;  // 0: every core
};

// The last frame's images: with accumulation, what the frames at rest converged to.
struct Images {
  Image direct;    // the direct stage (with emitters seen)
  Image indirect;  // the technique's indirect light; empty for "direct"
  Image color;     // the composite
};

// Renders job.frames frames of the scene's own camera.
inline Images render(const Scene& scene, const Job& job) {
  const ThreadLimit limit(job.threads);
  auto tracer = make_embree_tracer(scene);
  auto technique = make_technique(job.technique);
  for (const auto& [name, value] : job.params) technique->params().set(name, value);
  Renderer renderer(scene, *tracer, std::move(technique));
  FrameSettings settings;
  settings.width = job.width;
  settings.height = job.height;
  settings.light_samples = job.light_samples;
  settings.jitter = job.jitter;
  settings.seed = job.seed;
  settings.accumulate = job.accumulate;
  settings.denoise = job.denoise;
  const Frame* f = nullptr;
  for (int k = 0; k < job.frames; ++k) f = &renderer.render(scene.camera, settings);
  return {f->direct, f->indirect, f->color};
}

// The offline reference (path-traced, box-filtered pixels) of the scene's own camera.
inline Image path_reference(const Scene& scene, int width, int height, int spp, uint32_t seed = 0,
                            int max_bounces = -1) {
  auto tracer = make_embree_tracer(scene);
  ReferenceSettings settings;
  settings.width = width;
  settings.height = height;
  settings.spp = spp;
  settings.seed = seed;
  settings.path.max_bounces = max_bounces;
  return render_reference(scene, *tracer, scene.camera, settings).image;
}

}  // namespace bounce::render_test
