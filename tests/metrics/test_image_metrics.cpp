// Image metrics against values worked out by hand, and SSIM against a brute-force evaluation of
// Wang et al.'s formula.
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/core/rng.h"
#include "bounce/metrics/image_metrics.h"

namespace bounce {
namespace {

// An image whose every channel holds the same 8-bit sRGB code in each pixel, stored as the
// linear value that encodes to exactly that code.
Image grey_code_image(int w, int h, int code) {
  return Image(w, h, vec3(srgb_decode(float(code) / 255.0f)));
}

// A random image of 8-bit codes in [lo, hi], as linear values.
Image random_code_image(int w, int h, int lo, int hi, uint64_t seed) {
  Image image(w, h);
  Pcg32 rng(seed);
  for (vec3& p : image.pixels())
    for (int k = 0; k < 3; ++k)
      p[k] = srgb_decode(float(lo + int(rng.next_below(uint32_t(hi - lo + 1)))) / 255.0f);
  return image;
}

TEST(ImageMetrics, LinearValuesOfCodesRoundTripToTheSameCodes) {
  const Image image = random_code_image(7, 5, 0, 255, 1);
  const std::vector<uint8_t> codes = srgb8_values(image);
  Pcg32 rng(1);
  for (size_t i = 0; i < codes.size(); ++i) EXPECT_EQ(codes[i], int(rng.next_below(256))) << i;
}

TEST(ImageMetrics, IdenticalImages) {
  const Image a = random_code_image(20, 16, 0, 255, 2);
  const ImageComparison c = compare_images(a, a);
  for (const DomainMetrics* m : {&c.srgb8, &c.linear}) {
    EXPECT_EQ(m->mse, 0.0);
    EXPECT_EQ(m->nrmse, 0.0);
    EXPECT_TRUE(std::isinf(m->psnr_db));
    EXPECT_NEAR(m->mssim, 1.0, 1e-12);
    EXPECT_EQ(m->ssim_windows, 10 * 6);
  }
}

TEST(ImageMetrics, ConstantOffsetInEightBitCodes) {
  // Reference: code 100 everywhere but one pixel at 200 (so the range is 100); test: +10.
  const int w = 16, h = 12, d = 10;
  Image ref = grey_code_image(w, h, 100), test = grey_code_image(w, h, 100 + d);
  ref.at(3, 4) = vec3(srgb_decode(200.0f / 255.0f));
  test.at(3, 4) = vec3(srgb_decode(float(200 + d) / 255.0f));
  const ImageComparison c = compare_images(ref, test);
  EXPECT_DOUBLE_EQ(c.srgb8.mse, d * d);
  EXPECT_DOUBLE_EQ(c.srgb8.range, 100.0);
  EXPECT_DOUBLE_EQ(c.srgb8.nrmse, d / 100.0);
  EXPECT_NEAR(c.srgb8.psnr_db, 10.0 * std::log10(255.0 * 255.0 / (d * d)), 1e-12);
}

TEST(ImageMetrics, ConstantImagesSsimFollowsTheFormula) {
  // Two constant images: no variance, so SSIM = (2 x y + C1) / (x^2 + y^2 + C1) everywhere.
  const int x = 100, y = 130;
  const ImageComparison c = compare_images(grey_code_image(15, 13, x), grey_code_image(15, 13, y));
  const double c1 = sqr(0.01f * 255.0f);
  const double expected = (2.0 * x * y + c1) / (double(x) * x + double(y) * y + c1);
  EXPECT_NEAR(c.srgb8.mssim, expected, 1e-6);
  EXPECT_EQ(c.srgb8.ssim_windows, 5 * 3);
  EXPECT_DOUBLE_EQ(c.srgb8.mse, double(y - x) * (y - x));
}

TEST(ImageMetrics, OnePixelChangeInLinearValues) {
  // n pixels, one channel of one pixel changed by delta: MSE = delta^2 / (3 n).
  const int w = 8, h = 4;
  Image ref(w, h, vec3(0.25f)), test = ref;
  ref.at(0, 0) = vec3(0.0f);  // reference range [0, 1]
  ref.at(1, 0) = vec3(1.0f);
  test.at(0, 0) = vec3(0.0f);
  test.at(1, 0) = vec3(1.0f);
  const float delta = 0.5f;
  test.at(5, 2).y += delta;
  const ImageComparison c = compare_images(ref, test);
  const double mse = double(delta) * delta / (3.0 * w * h);
  EXPECT_DOUBLE_EQ(c.linear.mse, mse);
  EXPECT_DOUBLE_EQ(c.linear.range, 1.0);
  EXPECT_DOUBLE_EQ(c.linear.nrmse, std::sqrt(mse));
  EXPECT_NEAR(c.linear.psnr_db, 10.0 * std::log10(1.0 / mse), 1e-9);
  EXPECT_TRUE(std::isnan(c.linear.mssim)) << "8 x 4 is smaller than the SSIM window";
  EXPECT_EQ(c.linear.ssim_windows, 0);
}

TEST(ImageMetrics, PsnrOfAKnownMse) {
  // Every code off by 5 against a reference spanning 0..255: MSE 25, PSNR 20 log10(255 / 5).
  Image ref = grey_code_image(4, 4, 50), test = grey_code_image(4, 4, 55);
  ref.at(0, 0) = vec3(0.0f);
  test.at(0, 0) = vec3(srgb_decode(5.0f / 255.0f));
  ref.at(1, 0) = vec3(srgb_decode(250.0f / 255.0f));
  test.at(1, 0) = vec3(1.0f);
  const ImageComparison c = compare_images(ref, test);
  EXPECT_DOUBLE_EQ(c.srgb8.mse, 25.0);
  EXPECT_NEAR(c.srgb8.psnr_db, 20.0 * std::log10(255.0 / 5.0), 1e-12);
  EXPECT_NEAR(c.srgb8.psnr_db, 34.1514, 1e-4);
  EXPECT_DOUBLE_EQ(c.srgb8.nrmse, 5.0 / 250.0);
}

// SSIM written out straight from the paper: for every 11x11 window fully inside the image, the
// Gaussian-weighted means, variances and covariance, then the formula; MSSIM is their mean.
double brute_force_mssim(const std::vector<double>& x, const std::vector<double>& y, int w, int h,
                         double range) {
  double window[11][11], total = 0.0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) {
      window[i][j] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2.0 * 1.5 * 1.5));
      total += window[i][j];
    }
  const double c1 = std::pow(0.01 * range, 2), c2 = std::pow(0.03 * range, 2);
  double sum = 0.0;
  int count = 0;
  for (int y0 = 0; y0 + 11 <= h; ++y0)
    for (int x0 = 0; x0 + 11 <= w; ++x0) {
      double mx = 0, my = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          const double g = window[i][j] / total;
          mx += g * x[size_t(y0 + i) * w + x0 + j];
          my += g * y[size_t(y0 + i) * w + x0 + j];
        }
      double vx = 0, vy = 0, cov = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          const double g = window[i][j] / total;
          const double dx = x[size_t(y0 + i) * w + x0 + j] - mx;
          const double dy = y[size_t(y0 + i) * w + x0 + j] - my;
          vx += g * dx * dx;
          vy += g * dy * dy;
          cov += g * dx * dy;
        }
      sum += (2 * mx * my + c1) * (2 * cov + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
      ++count;
    }
  return sum / count;
}

TEST(ImageMetrics, SsimOfANoisyImageMatchesBruteForce) {
  const int w = 37, h = 29;
  // A smooth gradient with a bright square, and a noisy copy of it.
  Image ref(w, h), test(w, h);
  Pcg32 rng(9);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      vec3 v(0.1f + 0.6f * x / w, 0.2f + 0.5f * y / h, 0.3f);
      if (x > 10 && x < 20 && y > 8 && y < 18) v = vec3(0.9f, 0.8f, 0.7f);
      ref.at(x, y) = v;
      test.at(x, y) = glm::clamp(
          v + 0.08f * (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f), 0.0f,
          1.0f);
    }
  const ImageComparison c = compare_images(ref, test);
  // 8-bit: luma of the codes, L = 255.
  const std::vector<uint8_t> a = srgb8_values(ref), b = srgb8_values(test);
  std::vector<double> la, lb, lin_a, lin_b;
  for (int i = 0; i < w * h; ++i) {
    la.push_back(0.2126 * a[3 * i] + 0.7152 * a[3 * i + 1] + 0.0722 * a[3 * i + 2]);
    lb.push_back(0.2126 * b[3 * i] + 0.7152 * b[3 * i + 1] + 0.0722 * b[3 * i + 2]);
    lin_a.push_back(luminance(ref.pixels()[i]));
    lin_b.push_back(luminance(test.pixels()[i]));
  }
  EXPECT_NEAR(c.srgb8.mssim, brute_force_mssim(la, lb, w, h, 255.0), 1e-9);
  EXPECT_LT(c.srgb8.mssim, 0.99);
  EXPECT_GT(c.srgb8.mssim, 0.3);
  // Linear: L is the reference luminance's range.
  double lo = 1e30, hi = -1e30;
  for (double v : lin_a) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_NEAR(c.linear.ssim_range, hi - lo, 1e-6);
  EXPECT_NEAR(c.linear.mssim, brute_force_mssim(lin_a, lin_b, w, h, hi - lo), 1e-6);
  EXPECT_EQ(c.srgb8.ssim_windows, (w - 10) * (h - 10));
}

TEST(ImageMetrics, GaussianTapsAreNormalised) {
  const std::vector<double> taps = ssim_gaussian_taps();
  ASSERT_EQ(taps.size(), 11u);
  double sum = 0.0;
  for (double t : taps) sum += t;
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_NEAR(taps[4] / taps[5], std::exp(-1.0 / (2.0 * 1.5 * 1.5)), 1e-15);
}

TEST(ImageMetrics, DifferentSizesAreAnError) {
  EXPECT_THROW(compare_images(Image(4, 4), Image(4, 5)), Error);
  EXPECT_THROW(error_heat_map(Image(4, 4), Image(5, 4)), Error);
}

TEST(ImageMetrics, HeatMapRampsFromDarkToBright) {
  const Image ref = grey_code_image(4, 1, 100);
  Image test = ref;
  test.at(1, 0) = vec3(srgb_decode(110.0f / 255.0f));
  test.at(2, 0) = vec3(srgb_decode(120.0f / 255.0f));
  const HeatMap m = error_heat_map(ref, test, 20.0);
  EXPECT_DOUBLE_EQ(m.scale, 20.0);
  EXPECT_DOUBLE_EQ(m.max_error, 20.0);
  ASSERT_EQ(m.rgb.size(), 12u);
  EXPECT_EQ(m.rgb[0], 0);  // no error: the ramp's dark end
  EXPECT_EQ(m.rgb[2], 4);
  EXPECT_EQ(m.rgb[6], 252);  // full scale: the bright end
  EXPECT_EQ(m.rgb[7], 255);
  const int mid = m.rgb[3] + m.rgb[4] + m.rgb[5];
  EXPECT_GT(mid, m.rgb[0] + m.rgb[1] + m.rgb[2]);
  EXPECT_LT(mid, m.rgb[6] + m.rgb[7] + m.rgb[8]);
  // Automatic scale: the 99th percentile of the errors, at least 1.
  EXPECT_DOUBLE_EQ(error_heat_map(ref, ref).scale, 1.0);
}

}  // namespace
}  // namespace bounce
