// Image comparison against a reference, as DESIGN.md "Metrics" defines it: MSE, NRMSE, PSNR and
// SSIM/MSSIM (Wang et al. 2004), each on 8-bit sRGB values and on linear radiance.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/image.h"

namespace bounce {

// The metrics in one domain (8-bit sRGB values on a 0..255 scale, or linear radiance).
struct DomainMetrics {
  double mse = 0.0;         // squared difference averaged over pixels, then over the 3 channels
  double range = 0.0;       // max - min of the reference over all pixels and channels
  double nrmse = 0.0;       // sqrt(mse) / range; 0 when mse is 0, +inf when only the range is 0
  double peak = 0.0;        // the PSNR peak: 255 for 8-bit values, the reference's range for linear
  double psnr_db = 0.0;     // 10 log10(peak^2 / mse); +inf when mse is 0
  double ssim_range = 0.0;  // SSIM's L: 255 for 8-bit, the reference luminance's range for linear
  double mssim = 0.0;       // mean SSIM over the windows; NaN when the image is under 11x11
  int ssim_windows = 0;     // windows that lie fully inside the image: (w - 10) * (h - 10)
};

struct ImageComparison {
  int width = 0;
  int height = 0;
  DomainMetrics srgb8;   // after the PNG tone map at exposure 0: clamp to [0, 1], sRGB, 8 bits
  DomainMetrics linear;  // linear radiance as stored (EXR, PFM) or decoded from sRGB (PNG)
};

// Compares `test` against `reference`; throws Error when their sizes differ.
ImageComparison compare_images(const Image& reference, const Image& test);

// Building blocks, exposed for tests.

// The 8-bit sRGB values PNG output would hold (exposure 0), 3 per pixel, row-major.
std::vector<uint8_t> srgb8_values(const Image& image);

// Mean over all elements of (a - b)^2, for two arrays of n values.
double mean_squared_error(const double* a, const double* b, size_t n);

inline constexpr int kSsimWindow = 11;     // Gaussian window side
inline constexpr double kSsimSigma = 1.5;  // its standard deviation in pixels
inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;

struct SsimMap {
  int width = 0;             // w - 10: one value per window position fully inside the image
  int height = 0;            // h - 10
  std::vector<double> ssim;  // row-major
  double mean = 0.0;         // MSSIM; NaN when the map is empty
};

// SSIM of two w x h single-channel images with dynamic range L: local statistics under the
// normalised 11x11 Gaussian window (sigma 1.5), only at windows fully inside the image ("valid"
// filtering, as Wang et al.'s reference code does), C1 = (K1 L)^2, C2 = (K2 L)^2.
SsimMap ssim_map(const std::vector<double>& x, const std::vector<double>& y, int w, int h,
                 double dynamic_range);

// The normalised 1D Gaussian whose outer product is the SSIM window (11 taps summing to 1).
std::vector<double> ssim_gaussian_taps();

// An error heat map: per-pixel RMS over the channels of the 8-bit sRGB difference, through a
// black-purple-orange-yellow colour ramp from 0 to `scale` (scale <= 0: the 99th percentile of
// the per-pixel errors, at least 1).
struct HeatMap {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel, row-major from the top
  double scale = 0.0;        // the error that maps to the top of the ramp
  double max_error = 0.0;
};
HeatMap error_heat_map(const Image& reference, const Image& test, double scale = 0.0);

}  // namespace bounce
