// nvcc check of render/photon_path.h (and the emission it starts from): the per-path kernel as a
// GPU backend runs it, once counting each path's photons, once writing them to their slots.
#include "bounce/render/photon_path.h"

namespace bounce {

__global__ void count_photon_paths(SceneView scene, TraceView trace, PhotonEmitterView emitters,
                                   PhotonPass pass, uint32_t* counts, uint32_t* rays) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= pass.paths) return;
  counts[i] = trace_photon_path(
      scene, trace, emitters, pass, i, [](uint32_t, const PhotonDeposit&) {}, rays[i]);
}

__global__ void write_photon_paths(SceneView scene, TraceView trace, PhotonEmitterView emitters,
                                   PhotonPass pass, const uint32_t* first, PhotonView out) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= pass.paths) return;
  uint32_t rays;
  trace_photon_path(
      scene, trace, emitters, pass, i,
      [&](uint32_t k, const PhotonDeposit& d) { store_photon(out, first[i] + k, d); }, rays);
}

}  // namespace bounce
