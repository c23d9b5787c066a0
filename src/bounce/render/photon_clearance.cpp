#include "bounce/render/photon_clearance.h"

#include <array>

#include "bounce/core/parallel.h"
#include "bounce/render/photons.h"
#include "bounce/trace/tracer.h"

namespace bounce {

uint64_t compute_photon_clearance(const Tracer& tracer, float radius, PhotonBuffer& photons) {
  const size_t n = photons.size();
  photons.clearance.resize(n * kClearanceRays);
  photons.min_clearance.resize(n);
  const PhotonView view = photons.view();
  constexpr size_t kBatch = 32;  // photons per tracer call
  parallel_for((n + kBatch - 1) / kBatch,
               [&](size_t batch) {
                 std::array<Ray, kBatch * kClearanceRays> rays;
                 std::array<Hit, kBatch * kClearanceRays> hits;
                 const size_t begin = batch * kBatch, end = std::min(n, begin + kBatch);
                 size_t count = 0;
                 for (size_t i = begin; i < end; ++i) {
                   const ClearanceFrame f = clearance_frame(view, i);
                   for (int k = 0; k < kClearanceRays; ++k)
                     rays[count++] = clearance_ray(f, k, radius);
                 }
                 tracer.intersect(std::span<const Ray>(rays.data(), count),
                                  std::span<Hit>(hits.data(), count), false);
                 for (size_t i = begin, r = 0; i < end; ++i) {
                   float distance[kClearanceRays];
                   for (int k = 0; k < kClearanceRays; ++k, ++r)
                     distance[k] = clearance_distance(hits[r], radius);
                   store_clearance(view, i, distance);
                 }
               },
               4);
  return uint64_t(n) * kClearanceRays;
}

}  // namespace bounce
