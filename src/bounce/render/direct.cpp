#include "bounce/render/direct.h"

#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "bounce/core/parallel.h"

namespace bounce {

namespace {

// Shadow rays wait here with the radiance they carry until a batch is traced at once: the
// Tracer's stream call is what makes this stage fast on the CPU.
struct ShadowBatch {
  static constexpr size_t kCapacity = 1024;
  std::vector<Ray> rays;
  std::vector<vec3> radiance;
  std::vector<uint32_t> pixel;
  std::vector<uint8_t> blocked;
  uint64_t traced = 0;

  ShadowBatch() {
    rays.reserve(kCapacity);
    radiance.reserve(kCapacity);
    pixel.reserve(kCapacity);
    blocked.resize(kCapacity);
  }

  void flush(const Tracer& tracer, vec3* out) {
    tracer.occluded(rays, std::span<uint8_t>(blocked.data(), rays.size()));
    traced += rays.size();
    for (size_t k = 0; k < rays.size(); ++k)
      if (!blocked[k]) out[pixel[k]] += radiance[k];
    rays.clear();
    radiance.clear();
    pixel.clear();
  }
};

}  // namespace

uint64_t compute_direct(const SceneView& scene, const LightPickerView& lights, const Tracer& tracer,
                        const GBuffer& g, vec3 eye, const DirectSettings& settings, Image& out) {
  const ConstGBufferView view = g.view();
  vec3* pixels = out.pixels().data();
  tbb::enumerable_thread_specific<ShadowBatch> batches;
  parallel_for_tiles(g.width, g.height, 8, [&](int x0, int y0, int x1, int y1) {
    ShadowBatch& b = batches.local();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const uint32_t i = uint32_t(view.index(x, y));
        pixels[i] = view.emission[i];  // before the samples: a full batch adds to it at once
        auto shadow = [&](const Ray& ray, vec3 radiance) {
          b.rays.push_back(ray);
          b.radiance.push_back(radiance);
          b.pixel.push_back(i);
          if (b.rays.size() == ShadowBatch::kCapacity) b.flush(tracer, pixels);
        };
        direct_light_pixel(scene, lights, view, i, eye, settings, shadow);
      }
    b.flush(tracer, pixels);  // a tile's pixels are final before the tile ends
  });
  uint64_t total = 0;
  for (const ShadowBatch& b : batches) total += b.traced;
  return total;
}

}  // namespace bounce
