#include "bounce/metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/core/tonemap.h"

namespace bounce {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Rec. 709 luma weights, the same as core/color.h's luminance().
double luma(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// Sums of a plane under the window, horizontally then vertically, at valid positions only.
std::vector<double> filter_valid(const std::vector<double>& plane, int w, int h,
                                 const std::vector<double>& taps) {
  const int k = int(taps.size());
  const int ow = w - k + 1, oh = h - k + 1;
  std::vector<double> rows(size_t(ow) * h), out(size_t(ow) * oh);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int i = 0; i < k; ++i) s += taps[i] * plane[size_t(y) * w + x + i];
      rows[size_t(y) * ow + x] = s;
    }
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int i = 0; i < k; ++i) s += taps[i] * rows[size_t(y + i) * ow + x];
      out[size_t(y) * ow + x] = s;
    }
  return out;
}

DomainMetrics domain_metrics(const std::vector<double>& ref, const std::vector<double>& test,
                             const std::vector<double>& ref_luma,
                             const std::vector<double>& test_luma, int w, int h, double peak,
                             double ssim_range) {
  DomainMetrics m;
  m.mse = mean_squared_error(ref.data(), test.data(), ref.size());
  const auto [lo, hi] = std::minmax_element(ref.begin(), ref.end());
  m.range = *hi - *lo;
  const double rmse = std::sqrt(m.mse);
  m.nrmse = m.mse == 0.0 ? 0.0 : (m.range > 0.0 ? rmse / m.range : kInf);
  m.peak = peak;
  m.psnr_db = m.mse == 0.0 ? kInf : (peak > 0.0 ? 10.0 * std::log10(peak * peak / m.mse) : -kInf);
  m.ssim_range = ssim_range;
  const SsimMap map = ssim_map(ref_luma, test_luma, w, h, ssim_range);
  m.mssim = map.mean;
  m.ssim_windows = map.width * map.height;
  return m;
}

// Colour ramp (after matplotlib's "inferno" at 0, 1/4, 1/2, 3/4, 1): dark is small error.
vec3 ramp(double t) {
  static const vec3 stops[5] = {
      {0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(int(t), 3);
  const float f = float(t - i);
  return stops[i] + (stops[i + 1] - stops[i]) * f;
}

}  // namespace

std::vector<uint8_t> srgb8_values(const Image& image) {
  std::vector<uint8_t> out;
  tonemap_srgb8(image, 0.0f, out);
  return out;
}

double mean_squared_error(const double* a, const double* b, size_t n) {
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum / double(n);
}

std::vector<double> ssim_gaussian_taps() {
  std::vector<double> taps(kSsimWindow);
  double sum = 0.0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double d = i - kSsimWindow / 2;
    taps[i] = std::exp(-d * d / (2.0 * kSsimSigma * kSsimSigma));
    sum += taps[i];
  }
  // The 2D window is the outer product, so normalising each factor normalises the window.
  for (double& t : taps) t /= sum;
  return taps;
}

SsimMap ssim_map(const std::vector<double>& x, const std::vector<double>& y, int w, int h,
                 double dynamic_range) {
  SsimMap m;
  m.mean = std::numeric_limits<double>::quiet_NaN();
  if (w < kSsimWindow || h < kSsimWindow) return m;
  const std::vector<double> taps = ssim_gaussian_taps();
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  const std::vector<double> mu_x = filter_valid(x, w, h, taps);
  const std::vector<double> mu_y = filter_valid(y, w, h, taps);
  const std::vector<double> e_xx = filter_valid(xx, w, h, taps);
  const std::vector<double> e_yy = filter_valid(yy, w, h, taps);
  const std::vector<double> e_xy = filter_valid(xy, w, h, taps);
  const double c1 = (kSsimK1 * dynamic_range) * (kSsimK1 * dynamic_range);
  const double c2 = (kSsimK2 * dynamic_range) * (kSsimK2 * dynamic_range);
  m.width = w - kSsimWindow + 1;
  m.height = h - kSsimWindow + 1;
  m.ssim.resize(mu_x.size());
  double sum = 0.0;
  for (size_t i = 0; i < mu_x.size(); ++i) {
    const double mx = mu_x[i], my = mu_y[i];
    const double vx = e_xx[i] - mx * mx, vy = e_yy[i] - my * my, cov = e_xy[i] - mx * my;
    m.ssim[i] =
        ((2.0 * mx * my + c1) * (2.0 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
    sum += m.ssim[i];
  }
  m.mean = sum / double(m.ssim.size());
  return m;
}

ImageComparison compare_images(const Image& reference, const Image& test) {
  if (reference.width() != test.width() || reference.height() != test.height())
    fail("cannot compare images of different sizes: the reference is {}x{}, the test {}x{}",
         reference.width(), reference.height(), test.width(), test.height());
  if (reference.empty()) fail("cannot compare empty images");
  const int w = reference.width(), h = reference.height();
  const size_t n = reference.pixel_count();
  ImageComparison c;
  c.width = w;
  c.height = h;

  // 8-bit sRGB: the values a PNG of each image holds.
  {
    const std::vector<uint8_t> a8 = srgb8_values(reference), b8 = srgb8_values(test);
    std::vector<double> a(a8.begin(), a8.end()), b(b8.begin(), b8.end());
    std::vector<double> la(n), lb(n);
    for (size_t i = 0; i < n; ++i) {
      la[i] = luma(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
      lb[i] = luma(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
    }
    c.srgb8 = domain_metrics(a, b, la, lb, w, h, 255.0, 255.0);
  }
  // Linear radiance.
  {
    std::vector<double> a(3 * n), b(3 * n), la(n), lb(n);
    for (size_t i = 0; i < n; ++i) {
      const vec3 p = reference.pixels()[i], q = test.pixels()[i];
      for (int k = 0; k < 3; ++k) {
        a[3 * i + k] = p[k];
        b[3 * i + k] = q[k];
      }
      la[i] = luma(p.x, p.y, p.z);
      lb[i] = luma(q.x, q.y, q.z);
    }
    const auto [lo, hi] = std::minmax_element(a.begin(), a.end());
    const auto [llo, lhi] = std::minmax_element(la.begin(), la.end());
    // A constant reference has no range; SSIM then uses L = 1 so that its constants stay > 0.
    const double luma_range = *lhi - *llo > 0.0 ? *lhi - *llo : 1.0;
    c.linear = domain_metrics(a, b, la, lb, w, h, *hi - *lo, luma_range);
  }
  return c;
}

HeatMap error_heat_map(const Image& reference, const Image& test, double scale) {
  if (reference.width() != test.width() || reference.height() != test.height())
    fail("cannot compare images of different sizes: the reference is {}x{}, the test {}x{}",
         reference.width(), reference.height(), test.width(), test.height());
  const size_t n = reference.pixel_count();
  const std::vector<uint8_t> a = srgb8_values(reference), b = srgb8_values(test);
  std::vector<double> error(n);
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = double(a[3 * i + k]) - double(b[3 * i + k]);
      s += d * d;
    }
    error[i] = std::sqrt(s / 3.0);
  }
  HeatMap m;
  m.width = reference.width();
  m.height = reference.height();
  m.max_error = n ? *std::max_element(error.begin(), error.end()) : 0.0;
  if (scale <= 0.0 && n > 0) {
    std::vector<double> sorted = error;
    const size_t k = std::min(n - 1, size_t(0.99 * double(n)));
    std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
    scale = std::max(1.0, sorted[k]);
  }
  m.scale = scale;
  m.rgb.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    const vec3 c = ramp(error[i] / scale);
    for (int k = 0; k < 3; ++k) m.rgb[3 * i + k] = uint8_t(std::lround(c[k]));
  }
  return m;
}

}  // namespace bounce
