// nvcc check of the denoiser's per-pixel bodies (render/denoise_*.h): the temporal pass,
// the depth slope, the spatial variance's box sums, both a-trous kernels (3x3 and 5x5, with and
// without indirect light, with the column tests a GPU pixel needs), the half-resolution
// indirect light's downsample and upsample, and remodulation.
#include "bounce/render/denoise_atrous.h"
#include "bounce/render/denoise_half.h"
#include "bounce/render/denoise_kernels.h"
#include "bounce/render/denoise_temporal.h"
#include "bounce/render/denoise_variance.h"

namespace bounce {

namespace {

__device__ bool pixel_of(int width, int height, int& x, int& y) {
  x = int(blockIdx.x * blockDim.x + threadIdx.x);
  y = int(blockIdx.y * blockDim.y + threadIdx.y);
  return x < width && y < height;
}

}  // namespace

template <bool kIndirect, bool kRest>
__global__ void check_temporal(denoise::TemporalPass pass, bool* short_history) {
  int x, y;
  if (pixel_of(pass.width, pass.height, x, y))
    short_history[size_t(y) * size_t(pass.width) + size_t(x)] =
        denoise::temporal_pixel<kIndirect, kRest>(pass, x, y);
}
template __global__ void check_temporal<true, true>(denoise::TemporalPass, bool*);
template __global__ void check_temporal<false, false>(denoise::TemporalPass, bool*);

__global__ void check_depth_slope(const float* depth, int width, int height, float* slope) {
  int x, y;
  if (!pixel_of(width, height, x, y)) return;
  const size_t row = size_t(y) * size_t(width);
  const size_t up = y > 0 ? row - size_t(width) : row;
  const size_t down = y + 1 < height ? row + size_t(width) : row;
  slope[row + size_t(x)] = denoise::depth_slope_pixel<true>(depth, width, row, up, down, x);
}

__global__ void check_variance(denoise::BoxPass box, denoise::VariancePass variance) {
  int x, y;
  if (!pixel_of(variance.width, variance.height, x, y)) return;
  denoise::box_row_pixel(box, size_t(y) * size_t(box.width), x);
  denoise::spatial_variance_pixel(variance, x, y);  // (a real launch splits the two passes)
}

template <int kRadius, bool kIndirect, bool kVariance>
__global__ void check_atrous(denoise::AtrousPass pass) {
  int x, y;
  if (pixel_of(pass.width, pass.height, x, y))
    denoise::atrous_pixel<kRadius, kIndirect, kVariance>(pass, x, y);
}
template __global__ void check_atrous<1, true, true>(denoise::AtrousPass);
template __global__ void check_atrous<1, false, false>(denoise::AtrousPass);
template __global__ void check_atrous<2, true, true>(denoise::AtrousPass);
template __global__ void check_atrous<2, false, false>(denoise::AtrousPass);

__global__ void check_downsample(denoise::HalfDownsample pass, int half_height) {
  int x, y;
  if (pixel_of(pass.half_width, half_height, x, y)) denoise::downsample_pixel(pass, x, y);
}

__global__ void check_upsample(denoise::HalfUpsample pass) {
  int x, y;
  if (pixel_of(pass.width, pass.height, x, y)) denoise::upsample_pixel(pass, x, y);
}

__global__ void check_remodulate(denoise::RemodulatePass pass) {
  const size_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < pass.g.size()) denoise::remodulate_pixel<true, false>(pass, i);
}

}  // namespace bounce
