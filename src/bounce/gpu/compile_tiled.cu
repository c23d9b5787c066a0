// nvcc check of techniques/tiled/tiled_kernels.h: the gather at a pixel (screen tiles or hash
// grid), the low-resolution estimate and the upsampling with edge re-estimation.
#include "bounce/techniques/tiled/tiled_kernels.h"

namespace bounce {

__global__ void check_estimate_low_res(TiledGatherView gather, LowResView low) {
  const int lx = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int ly = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (lx < low.width && ly < low.height) estimate_low_res(gather, low, lx, ly);
}

__global__ void check_upsample(TiledGatherView gather, ConstLowResView low, EdgeTest edges,
                               ImageView out, uint8_t* edge) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (x < out.width && y < out.height)
    edge[gather.g.index(x, y)] =
        upsample_pixel(gather, low, edges, upsample_row(low, y), out, x, y) ? 1 : 0;
}

__global__ void check_gather(TiledGatherView gather, ImageView out) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (x < out.width && y < out.height) out.at(x, y) = gather_pixel(gather, x, y);
}

}  // namespace bounce
