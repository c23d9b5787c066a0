// nvcc check of render/photon_clearance.h: the per-photon clearance rays through the trace view.
#include "bounce/render/photon_clearance.h"

namespace bounce {

__global__ void check_photon_clearance(TraceView trace, PhotonView photons, float radius) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= photons.count) return;
  photon_clearance(trace, photons, i, radius);
}

}  // namespace bounce
