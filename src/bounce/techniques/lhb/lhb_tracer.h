// Embree's closest-hit question answered by the layered hit buffers, for arbitrary rays: each
// ray's direction snaps to the nearest buffer direction (the direction set's lookup, passed in)
// and the buffers answer along it. Lets the buffers and a Tracer be compared on identical rays
// (tests, bench/bench_lhb.cpp).
#pragma once

#include <functional>
#include <span>

#include "bounce/core/math.h"
#include "bounce/techniques/lhb/layered_hit_buffers.h"
#include "bounce/trace/ray.h"

namespace bounce {

class LhbTracer {
 public:
  // nearest(unit direction) -> index of the buffer direction nearest to it.
  using Nearest = std::function<int(vec3)>;

  LhbTracer(const LayeredHitBuffers& buffers, Nearest nearest)
      : buffers_(buffers), nearest_(std::move(nearest)) {}

  // The closest hit along the snapped direction; t is measured along that direction.
  Hit intersect(const Ray& ray) const;
  // A stream of rays, in parallel; hits.size() must equal rays.size().
  void intersect(std::span<const Ray> rays, std::span<Hit> hits) const;

 private:
  const LayeredHitBuffers& buffers_;
  Nearest nearest_;
};

}  // namespace bounce
