// Running the vertex technique in tests: a Renderer around it, frames, and the technique itself
// to look into (its tree, ring and estimates).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bounce/render/renderer.h"
#include "bounce/techniques/vertex/vertex.h"

namespace bounce::vertex_test {

struct VertexRun {
  std::unique_ptr<Tracer> tracer;
  std::unique_ptr<Renderer> renderer;
  VertexPhotonMapping* technique = nullptr;
  FrameSettings settings;

  VertexRun(const Scene& scene, const std::vector<std::pair<std::string, std::string>>& params,
            int size = 16) {
    tracer = make_embree_tracer(scene);
    auto t = std::make_unique<VertexPhotonMapping>();
    for (const auto& [name, value] : params) t->params().set(name, value);
    technique = t.get();
    renderer = std::make_unique<Renderer>(scene, *tracer, std::move(t));
    settings.width = settings.height = size;
    settings.light_samples = 4;
  }
  const Frame& frame(const Scene& scene) { return renderer->render(scene.camera, settings); }
  // Irradiance the photon map gives at x on the side n faces (the last frame's map and settings).
  vec3 irradiance(vec3 x, vec3 n) const {
    KnnHeap heap;
    return photon_irradiance(technique->photon_map(), x, n, technique->estimate_settings(), heap);
  }
};

}  // namespace bounce::vertex_test
