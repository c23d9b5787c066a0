// nvcc check of the vertex technique's kernels: photon paths (vertex_photon_path.h), the kd-tree's
// k-nearest search and the estimate (photon_kdtree.h, vertex_estimate.h), and the per-pixel
// locate and interpolation (vertex_kernels.h).
#include "bounce/core/image_view.h"
#include "bounce/techniques/vertex/vertex_kernels.h"
#include "bounce/techniques/vertex/vertex_photon_path.h"

namespace bounce {

__global__ void check_vertex_paths(VertexTraceView v, PhotonEmitterView emitters,
                                   const VertexPathStart* starts, uint32_t count,
                                   uint32_t* stored) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  uint32_t n = 0;
  auto deposit = [&](vec3, vec3, vec3) { ++n; };
  trace_vertex_path(v, emit_vertex_photon(v.scene, emitters, starts[i]), i, deposit);
  stored[i] = n;
}

__global__ void check_vertex_locate(VertexPixelView v) {
  const size_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < v.g.size()) locate_pixel(v, i);
}

__global__ void check_vertex_estimate(VertexEstimateView v, const uint32_t* slots, uint32_t count) {
  const uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j < count) estimate_slot(v, slots[j]);
}

__global__ void check_vertex_interpolate(VertexPixelView v, const vec3* irradiance, ImageView out) {
  const size_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < v.g.size()) out.pixels[i] = interpolate_pixel(v, irradiance, i);
}

}  // namespace bounce
