// nvcc check of the denoiser's per-pixel bodies (render/denoise_kernels.h): demodulation, the
// temporal pass, the variance estimate, both a-trous kernels (3x3 and 5x5, with and without
// indirect light, with the column tests a GPU pixel needs) and remodulation.
#include "bounce/render/denoise_kernels.h"

namespace bounce {

namespace {

__device__ bool pixel_of(int width, int height, int& x, int& y) {
  x = int(blockIdx.x * blockDim.x + threadIdx.x);
  y = int(blockIdx.y * blockDim.y + threadIdx.y);
  return x < width && y < height;
}

}  // namespace

__global__ void check_demodulate(denoise::DemodulatePass pass) {
  const size_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < pass.g.size()) denoise::demodulate_pixel(pass, i);
}

__global__ void check_temporal(denoise::TemporalPass pass) {
  int x, y;
  if (pixel_of(pass.width, pass.height, x, y)) denoise::temporal_pixel(pass, x, y);
}

__global__ void check_variance(denoise::VariancePass pass) {
  int x, y;
  if (pixel_of(pass.width, pass.height, x, y)) denoise::variance_pixel(pass, x, y);
}

template <int kRadius, bool kIndirect>
__global__ void check_atrous(denoise::AtrousPass pass) {
  int x, y;
  if (!pixel_of(pass.width, pass.height, x, y)) return;
  const denoise::AtrousRows<kRadius> rows = denoise::atrous_rows<kRadius>(pass, y);
  denoise::atrous_pixel<kRadius, kIndirect, true>(pass, rows, x);
}
template __global__ void check_atrous<1, true>(denoise::AtrousPass);
template __global__ void check_atrous<1, false>(denoise::AtrousPass);
template __global__ void check_atrous<2, true>(denoise::AtrousPass);
template __global__ void check_atrous<2, false>(denoise::AtrousPass);

__global__ void check_remodulate(denoise::RemodulatePass pass, size_t n) {
  const size_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) denoise::remodulate_pixel(pass, i);
}

}  // namespace bounce
