// BvhTracer: the Tracer on our own BVH (bvh.h), on the CPU. Every query, single or in streams,
// runs the traversal kernels run (bvh_traversal.h), so it is also how the GPU's answers are
// checked on a machine without one. Its view() carries the BVH and no Embree scene.
#pragma once

#include <memory>

#include "bounce/trace/bvh.h"
#include "bounce/trace/cutouts.h"
#include "bounce/trace/tracer.h"

namespace bounce {

class BvhTracer final : public Tracer {
 public:
  explicit BvhTracer(const Scene& scene) { rebuild(scene); }

  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  // Streams trace ray by ray (coherence changes nothing here).
  void intersect(std::span<const Ray> rays, std::span<Hit> hits,
                 bool coherent = false) const override;
  void occluded(std::span<const Ray> rays, std::span<uint8_t> blocked) const override;
  TraceView view() const override;
  void rebuild(const Scene& scene) override;
  // Refits the BVH for the moved meshes (a rebuild when one changed its counts) and takes the
  // sphere lights again.
  void update(const Scene& scene, std::span<const uint32_t> moved_meshes) override;
  TracerStats stats() const override;

  // The BVH itself, for a backend that copies its arrays elsewhere.
  const Bvh& bvh() const { return bvh_; }

 private:
  Bvh bvh_;
  std::vector<TraceSphere> spheres_;  // the scene's sphere lights
  Cutouts cutouts_;                   // alpha-masked holes, carried by view()
};

}  // namespace bounce
