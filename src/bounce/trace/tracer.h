// Tracer: the one narrow interface for ray queries. Embree implements it on the CPU; our own BVH
// (bvh.h) implements it too, on the CPU (BvhTracer) and as the traversal CUDA kernels run. Hits
// name the mesh and the triangle within it, or the sphere light the ray ended on: sphere lights are
// geometry for every query (see trace_view.h).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/ray.h"
#include "bounce/trace/trace_view.h"

namespace bounce {

struct TracerStats {
  size_t memory_bytes = 0;  // acceleration structure and scene copies
  double build_ms = 0.0;
};

class Tracer {
 public:
  virtual ~Tracer() = default;
  virtual Hit intersect(const Ray& ray) const = 0;
  virtual bool occluded(const Ray& ray) const = 0;
  // Streams of rays. `coherent` says the rays are coherent (primary rays in pixel order), which
  // lets the implementation trace them as packets or coherent streams.
  virtual void intersect(std::span<const Ray> rays, std::span<Hit> hits,
                         bool coherent = false) const = 0;
  virtual void occluded(std::span<const Ray> rays, std::span<uint8_t> blocked) const = 0;
  // The same queries for kernel bodies: a plain handle, valid until the next rebuild or update.
  virtual TraceView view() const = 0;
  // Rebuilds after the scene's geometry changed.
  virtual void rebuild(const Scene& scene) = 0;
  // Catches up with meshes whose vertices moved (same vertex and triangle counts): the
  // implementation refits their part of the acceleration structure where it can. Also takes the
  // sphere lights' current places and sizes, so call it when lights changed too (with no meshes).
  virtual void update(const Scene& scene, std::span<const uint32_t> moved_meshes) = 0;
  virtual TracerStats stats() const = 0;
};

// The scene's sphere lights as trace geometry, in light order.
std::vector<TraceSphere> trace_spheres(const Scene& scene);

enum class BuildQuality { kLow, kMedium, kHigh };

std::unique_ptr<Tracer> make_embree_tracer(const Scene& scene,
                                           BuildQuality quality = BuildQuality::kHigh);
// The Tracer on our own BVH (bvh_tracer.h).
std::unique_ptr<Tracer> make_bvh_tracer(const Scene& scene);

}  // namespace bounce
