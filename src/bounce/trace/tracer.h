// Tracer: the one narrow interface for ray queries. Embree implements it on the CPU; a BVH of our
// own will implement it for CUDA. Hits name the mesh and the triangle within it.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>

#include "bounce/core/math.h"
#include "bounce/scene/scene.h"

namespace bounce {

struct Ray {
  vec3 origin{0.0f};
  float tmin = 0.0f;
  vec3 direction{0.0f, 0.0f, 1.0f};
  float tmax = std::numeric_limits<float>::infinity();
};

struct Hit {
  static constexpr uint32_t kNone = 0xFFFFFFFFu;
  float t = std::numeric_limits<float>::infinity();
  uint32_t mesh = kNone;
  uint32_t triangle = 0;
  vec2 barycentric{0.0f};  // weights of the triangle's vertices 1 and 2

  bool valid() const { return mesh != kNone; }
};

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
  // Rebuilds after the scene's geometry changed.
  virtual void rebuild(const Scene& scene) = 0;
  // Catches up with meshes whose vertices moved (same vertex and triangle counts): the
  // implementation refits their part of the acceleration structure where it can.
  virtual void update(const Scene& scene, std::span<const uint32_t> moved_meshes) = 0;
  virtual TracerStats stats() const = 0;
};

enum class BuildQuality { kLow, kMedium, kHigh };

std::unique_ptr<Tracer> make_embree_tracer(const Scene& scene,
                                           BuildQuality quality = BuildQuality::kHigh);

}  // namespace bounce
