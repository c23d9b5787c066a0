// nvcc check of trace/trace_view.h: closest hit and occlusion, sphere lights included.
#include "bounce/trace/trace_view.h"

namespace bounce {

__global__ void check_trace_view(TraceView trace, const Ray* rays, uint32_t n, Hit* hits,
                                 uint8_t* blocked) {
  const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  hits[i] = trace.intersect(rays[i]);
  blocked[i] = trace.occluded(rays[i]) ? 1 : 0;
}

}  // namespace bounce
