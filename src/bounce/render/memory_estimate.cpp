#include "bounce/render/memory_estimate.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "bounce/render/photon_path.h"

namespace bounce {

double expected_photon_deposits(const Scene& scene, int max_bounces) {
  if (max_bounces >= 0) return double(std::min(max_bounces, kMaxPhotonDepth));
  const double cap = double(kMaxPhotonDepth);
  float survive = 0.0f;
  for (const Material& m : scene.materials) survive = std::max(survive, max_component(m.albedo));
  if (survive >= 1.0f) return cap;
  return std::min(cap, double(survive) / (1.0 - double(survive)));
}

uint64_t saturating_bytes(double product) {
  constexpr double kMax = double(std::numeric_limits<uint64_t>::max());
  return !(product < kMax) ? std::numeric_limits<uint64_t>::max() : uint64_t(product);
}

}  // namespace bounce
