// nvcc check of the lhb technique's kernels: the deep rasterizer with its alpha test
// (deep_raster_kernels.h), the buffer query (lhb_query.h), and the per-pixel gather and
// discontinuity filter (lhb_kernels.h). Nothing launches them on the GPU yet.
#include "bounce/techniques/lhb/deep_raster_kernels.h"
#include "bounce/techniques/lhb/lhb_kernels.h"

namespace bounce {

// One direction per block, as the CPU runs one direction per task.
__global__ void check_lhb_raster(const LhbFrame* frames, int size, MeshView mesh,
                                 uint32_t mesh_index, uint32_t first_prim, CutoutView cutouts,
                                 LhbProjected* scratch, LhbSlabOut out, LhbRasterStats* stats) {
  if (threadIdx.x != 0) return;
  LhbRasterStats s;
  lhb_raster_mesh(frames[blockIdx.x], size, mesh, mesh_index, first_prim, true, cutouts,
                  scratch + size_t(blockIdx.x) * mesh.vertex_count, out, s);
  stats[blockIdx.x] = s;
}

// One thread per (triangle, direction) pair, the seed's layout (with atomics on a real launch).
__global__ void check_lhb_triangle(LhbFrame f, int size, MeshView mesh, CutoutView cutouts,
                                   LhbSlabOut out, LhbRasterStats* stats) {
  const uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= mesh.triangle_count) return;
  const uvec3 i = mesh.triangles[t];
  lhb_raster_triangle(f, size, mesh.positions[i.x], mesh.positions[i.y], mesh.positions[i.z], t,
                      true, cutouts, 0, t, out, stats[t]);
}

__global__ void check_lhb_pixel(LhbScene ls, LhbGatherSettings settings, ConstGBufferView g,
                                vec3* incoming, uint64_t* rays) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y);
  if (x >= g.width || y >= g.height) return;
  PathCounters counters;
  incoming[g.index(x, y)] = lhb_pixel(ls, settings, g, x, y, counters);
  atomicAdd(reinterpret_cast<unsigned long long*>(rays), (unsigned long long)counters.rays);
}

__global__ void check_lhb_discontinuity(ConstGBufferView g, const vec3* incoming, int n,
                                        float normal_dot, float distance, vec3* out) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x), y = int(blockIdx.y);
  if (x < g.width && y < g.height)
    out[g.index(x, y)] = lhb_discontinuity_pixel(g, incoming, x, y, n, normal_dot, distance);
}

}  // namespace bounce
