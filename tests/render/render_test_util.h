// Rendering a scene in tests: frames through the pipeline with a technique set up by parameter
// name, and the offline path-traced reference to compare them with.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/render/renderer.h"
#include "bounce/techniques/path/reference.h"

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
  uint32_t seed = 0;
  int threads = 0;  // 0: every core
};

struct Images {
  Image direct;    // the direct stage (with emitters seen), averaged over the frames
  Image indirect;  // the technique's last indirect image; empty for "direct"
  Image color;     // the composite, averaged over the frames

  // Averaged direct light plus the last indirect image: what a technique that averages its own
  // indirect light over frames (progressive passes, accumulation) has converged to.
  Image direct_plus_last_indirect() const {
    return indirect.pixel_count() == 0 ? direct : direct + indirect;
  }
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
  Images out{Image(job.width, job.height), Image(), Image(job.width, job.height)};
  for (int k = 0; k < job.frames; ++k) {
    const Frame& f = renderer.render(scene.camera, settings);
    out.direct += f.direct;
    out.color += f.color;
    out.indirect = f.indirect;
  }
  const float inv_frames = 1.0f / float(job.frames);
  out.direct = out.direct * inv_frames;
  out.color = out.color * inv_frames;
  return out;
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
