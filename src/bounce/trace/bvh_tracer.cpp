#include "bounce/trace/bvh_tracer.h"

#include "bounce/trace/bvh_traversal.h"
#include "bounce/trace/cutouts.h"

namespace bounce {

Hit BvhTracer::intersect(const Ray& ray) const {
  return view().intersect(ray);
}

bool BvhTracer::occluded(const Ray& ray) const {
  return view().occluded(ray);
}

void BvhTracer::intersect(std::span<const Ray> rays, std::span<Hit> hits, bool) const {
  const TraceView v = view();
  for (size_t i = 0; i < rays.size(); ++i) hits[i] = v.intersect(rays[i]);
}

void BvhTracer::occluded(std::span<const Ray> rays, std::span<uint8_t> blocked) const {
  const TraceView v = view();
  for (size_t i = 0; i < rays.size(); ++i) blocked[i] = v.occluded(rays[i]) ? 1 : 0;
}

TraceView BvhTracer::view() const {
  TraceView v;
  v.spheres = spheres_.data();
  v.sphere_count = uint32_t(spheres_.size());
  v.bvh = bvh_.view();
  v.bvh.cutouts = cutouts_.view();
  return v;
}

void BvhTracer::rebuild(const Scene& scene) {
  spheres_ = trace_spheres(scene);
  bvh_.build(scene);
  cutouts_.build(scene);
}

void BvhTracer::update(const Scene& scene, std::span<const uint32_t> moved_meshes) {
  spheres_ = trace_spheres(scene);
  if (!moved_meshes.empty()) bvh_.refit(scene, moved_meshes);
  if (!moved_meshes.empty() && !cutouts_.fits(scene)) cutouts_.build(scene);
}

TracerStats BvhTracer::stats() const {
  return {bvh_.memory_bytes() + spheres_.size() * sizeof(TraceSphere), bvh_.build_ms()};
}

std::unique_ptr<Tracer> make_bvh_tracer(const Scene& scene) {
  return std::make_unique<BvhTracer>(scene);
}

}  // namespace bounce
