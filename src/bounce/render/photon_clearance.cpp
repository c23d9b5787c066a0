#include "bounce/render/photon_clearance.h"

#include <array>

#include "bounce/core/octahedral.h"
#include "bounce/core/parallel.h"

namespace bounce {

uint64_t compute_photon_clearance(const Tracer& tracer, float radius, PhotonBuffer& photons) {
  const size_t n = photons.size();
  photons.clearance.resize(n * kClearanceRays);
  photons.min_clearance.resize(n);
  constexpr size_t kBatch = 32;  // photons per tracer call
  parallel_for((n + kBatch - 1) / kBatch,
               [&](size_t batch) {
                 std::array<Ray, kBatch * kClearanceRays> rays;
                 std::array<Hit, kBatch * kClearanceRays> hits;
                 const size_t begin = batch * kBatch, end = std::min(n, begin + kBatch);
                 size_t count = 0;
                 for (size_t i = begin; i < end; ++i) {
                   const vec3 normal = photons.normal_dir[i];
                   const Basis frame = Basis::from_normal(normal);
                   // Just above the surface, so the rays skim it instead of hitting it.
                   const vec3 origin = offset_origin(photons.position[i], normal);
                   for (int k = 0; k < kClearanceRays; ++k)
                     rays[count++] = Ray{origin, 0.0f, clearance_direction(frame, k), radius};
                 }
                 tracer.intersect(std::span<const Ray>(rays.data(), count),
                                  std::span<Hit>(hits.data(), count), false);
                 for (size_t i = begin, r = 0; i < end; ++i)
                   for (int k = 0; k < kClearanceRays; ++k, ++r)
                     photons.clearance[i * kClearanceRays + k] =
                         hits[r].valid() ? hits[r].t : radius;
               },
               4);
  return uint64_t(n) * kClearanceRays;
}

}  // namespace bounce
