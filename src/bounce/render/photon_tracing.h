// Photon emission and tracing (seed 000 §5.3.1-5.3.2, multi-bounce): photon paths leave the
// lights, chosen in proportion to their power, from Hammersley points on the emitters in
// cosine-weighted directions; a photon is stored at every diffuse hit after the first (the first
// hit is direct light, which the direct stage computes).
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/render/photons.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/tracer.h"

namespace bounce {

// Paths ended by Russian roulette still stop here (a closed white room would never end).
inline constexpr int kMaxPhotonDepth = 64;

struct PhotonTraceSettings {
  uint32_t paths = 10000;  // photon paths per pass
  int max_bounces = -1;    // -1: unlimited, ended by Russian roulette; B >= 0: bounces 1..B
  uint32_t seed = 0;       // decorrelates runs
  uint32_t pass = 0;       // progressive passes use distinct photon sets
};

struct PhotonTraceStats {
  uint64_t paths = 0;
  uint64_t stored = 0;
  uint64_t rays = 0;
  vec3 emitted_power{0.0f};  // W: the total power of the lights the paths were drawn from
};

// Traces one pass of photons into `out` (replacing its contents). Deterministic: the photons and
// their order depend only on the scene and the settings, never on the thread count.
class PhotonTracer {
 public:
  PhotonTraceStats trace(const Scene& scene, const Tracer& tracer,
                         const PhotonTraceSettings& settings, PhotonBuffer& out);

 private:
  std::vector<PhotonBuffer> chunks_;  // per chunk of paths, concatenated in chunk order
};

}  // namespace bounce
