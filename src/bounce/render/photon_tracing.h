// Photon emission and tracing (seed 000 §5.3.1-5.3.2, multi-bounce): photon paths leave the
// lights, chosen in proportion to their power, from Hammersley points on the emitters in
// cosine-weighted directions; a photon is stored at every diffuse hit after the first (the first
// hit is direct light, which the direct stage computes). The bodies are in photon_path.h; this is
// the CPU launcher.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/render/photon_path.h"
#include "bounce/render/photons.h"
#include "bounce/scene/scene.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/tracer.h"

namespace bounce {

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

// The pass's shared values for these settings; paths == 0 when there is nothing to trace.
PhotonPass photon_pass(const PhotonTraceSettings& settings);

// Traces one pass of photons into `out` (replacing its contents): path by path, each path's
// photons in bounce order, at slots from count-then-scan. Deterministic: the photons and their
// order depend only on the scene and the settings, never on the thread count.
class PhotonTracer {
 public:
  // `view` is the scene's (SceneData) view; the emitters are set up from `scene`.
  PhotonTraceStats trace(const Scene& scene, const SceneView& view, const Tracer& tracer,
                         const PhotonTraceSettings& settings, PhotonBuffer& out);
  // For one-off passes: makes the scene's view for this call only.
  PhotonTraceStats trace(const Scene& scene, const Tracer& tracer,
                         const PhotonTraceSettings& settings, PhotonBuffer& out);

 private:
  // One chunk's photons as they were deposited (bounce by bounce), with where each goes.
  struct Chunk {
    std::vector<PhotonDeposit> photons;
    std::vector<uint32_t> path;  // path index of each photon
    std::vector<uint32_t> rank;  // its place among its path's photons
  };
  std::vector<Chunk> chunks_;
  std::vector<uint32_t> first_;  // per path: its count, then (after the scan) its first slot
};

}  // namespace bounce
