// LDR-FLIP (Andersson et al., HPG 2020) against values worked out by hand from the paper's
// formulas, in cases where its filters reduce to something simple: on a flat image the contrast
// sensitivity filters (normalised) return the image and the feature detectors (positive and
// negative taps summing to +1 and -1) return 0; at 1 pixel per degree the filters are 1 pixel
// wide (their off-centre taps are below 1e-100) and the detectors become the central difference
// [1, 0, -1] and the second difference [1/2, -1, 1/2].
#include <gtest/gtest.h>

#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/core/rng.h"
#include "bounce/metrics/flip.h"

namespace bounce {
namespace {

// The hand computation shared by the cases below (numbers to 6 digits):
//   sRGB -> linear: the standard curve; linear -> XYZ: the sRGB D65 matrix; white = XYZ(1, 1, 1)
//   = (0.950429, 1, 1.088900).
//   L*a*b* relative to that white, Hunt-adjusted (a, b scaled by L / 100):
//     green (0, 1, 0): L 87.7362, a -86.1787, b 83.1826 -> Hunt (87.7362, -75.6099, 72.9812)
//     blue  (0, 0, 1): L 32.2982, a  79.1936, b -107.859 -> Hunt (32.2982, 25.5781, -34.8364)
//   HyAB(green, blue) = |87.7362 - 32.2982| + sqrt(101.188^2 + 107.818^2) = 203.302
//   cmax = 203.302^0.7 = 41.2761; the knee pc * cmax = 16.5104.
//   remap(h): e = h^0.7; e < knee: 0.95 e / knee; else 0.95 + 0.05 (e - knee) / (cmax - knee).
constexpr double kCmax = 41.2761;
double remap_by_hand(double hyab) {
  const double e = std::pow(hyab, 0.7), knee = 0.4 * kCmax;
  return e < knee ? 0.95 * e / knee : 0.95 + 0.05 * (e - knee) / (kCmax - knee);
}

std::vector<float> flat(int w, int h, float r, float g, float b) {
  std::vector<float> v(size_t(w) * h * 3);
  for (size_t i = 0; i < v.size(); i += 3) {
    v[i] = r;
    v[i + 1] = g;
    v[i + 2] = b;
  }
  return v;
}

std::vector<float> random_srgb(int w, int h, uint64_t seed) {
  std::vector<float> v(size_t(w) * h * 3);
  Pcg32 rng(seed);
  for (float& x : v) x = rng.next_float();
  return v;
}

TEST(Flip, IdenticalImagesAreZeroEverywhere) {
  const std::vector<float> a = random_srgb(23, 17, 1);
  const FlipMap m = flip_srgb(a, a, 23, 17);
  EXPECT_EQ(m.mean, 0.0);
  for (float e : m.error) EXPECT_EQ(e, 0.0f);
}

TEST(Flip, FlatBlackAgainstWhiteMatchesTheHandValue) {
  // Black: L* 0. White: XYZ = the white, so L* 100, a* = b* = 0. HyAB = 100; 100^0.7 = 25.1189
  // is past the knee: 0.95 + 0.05 (25.1189 - 16.5104) / (41.2761 - 16.5104) = 0.967380.
  // No features on flat images, so FLIP = colour error^(1 - 0) in every pixel.
  const FlipMap m = flip_srgb(flat(24, 24, 0, 0, 0), flat(24, 24, 1, 1, 1), 24, 24);
  EXPECT_NEAR(remap_by_hand(100.0), 0.967380, 1e-6);
  for (float e : m.error) ASSERT_NEAR(e, 0.967380, 2e-5);
  EXPECT_NEAR(m.mean, 0.967380, 2e-5);
}

TEST(Flip, FlatGreyStepMatchesTheHandValue) {
  // sRGB 0.5 -> linear 0.214041 -> L* 116 * 0.214041^(1/3) - 16 = 53.3890; sRGB 0.6 -> 0.318547
  // -> L* 63.2226. Greys have a* = b* = 0, so HyAB = 9.83363; 9.83363^0.7 = 4.95336, below
  // the knee: 0.95 * 4.95336 / 16.5104 = 0.285013.
  const FlipMap m =
      flip_srgb(flat(16, 16, 0.5f, 0.5f, 0.5f), flat(16, 16, 0.6f, 0.6f, 0.6f), 16, 16);
  EXPECT_NEAR(remap_by_hand(9.83363), 0.285013, 1e-5);
  EXPECT_NEAR(m.mean, 0.285013, 2e-5);
  EXPECT_NEAR(m.error[0], 0.285013, 2e-5);
}

TEST(Flip, FlatGreenAgainstBlueIsTheLargestError) {
  // cmax is defined as this very pair's distance^0.7, which remaps to exactly 1.
  const FlipMap m = flip_srgb(flat(16, 16, 0, 1, 0), flat(16, 16, 0, 0, 1), 16, 16);
  EXPECT_NEAR(m.mean, 1.0, 1e-5);
}

TEST(Flip, SharpEdgeAtOnePixelPerDegreeMatchesTheHandValue) {
  // Reference: columns 0-3 black, 4-7 white; test: all white; 8 x 4 pixels, 1 pixel per degree.
  // Colour (the filters are the identity): columns 0-3 differ by black/white, E = 0.967380;
  // columns 4-7 are equal, 0.
  // Features on the achromatic channel normalised to [0, 1] (relative luminance Y: black 0,
  // white 1), border pixels replicated; rows are equal so the y detectors give 0:
  //   edge at column 3: Y(2) - Y(4) = -1, column 4: Y(3) - Y(5) = -1 (magnitude 1), else 0;
  //   point at column 3: Y(2)/2 - Y(3) + Y(4)/2 = 1/2, column 4: -1/2, else 0.
  // The test is flat (no features), so the feature difference is max(1, 1/2) = 1 at columns 3 and
  // 4, and the feature error (1 / sqrt 2)^0.5 = 2^-0.25 = 0.840896.
  // FLIP: columns 0-2: E; column 3: E^(1 - 0.840896) = 0.994737; columns 4-7: 0^(...) = 0.
  // Mean: (3 * 0.967380 + 0.994737) / 8 = 0.487110.
  std::vector<float> ref = flat(8, 4, 1, 1, 1);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) ref[3 * (size_t(y) * 8 + x) + c] = 0.0f;
  const FlipMap m = flip_srgb(ref, flat(8, 4, 1, 1, 1), 8, 4, 1.0);
  const double expected[8] = {0.967380, 0.967380, 0.967380, 0.994737, 0, 0, 0, 0};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) EXPECT_NEAR(m.error[size_t(y) * 8 + x], expected[x], 2e-5) << x;
  EXPECT_NEAR(m.mean, 0.487110, 2e-5);
}

TEST(Flip, SharpEdgeRaisesTheErrorOnlyNearTheEdge) {
  // Reference: black left of column 32, white from it; test: all white; 67 pixels per degree.
  // The colour filters reach 10 pixels and the detectors 9: beyond that from the edge the error
  // is the flat value E = 0.967380 (black side) or 0 (white side). Nearer the edge on the black
  // side the colour filters blend white into the reference, so its colour is no farther from
  // the test's white than black is and the colour error is at most E: an error above E there
  // comes from the feature term alone (the reference has an edge, the test none).
  const int w = 64, h = 8;
  std::vector<float> ref = flat(w, h, 1, 1, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x)
      for (int c = 0; c < 3; ++c) ref[3 * (size_t(y) * w + x) + c] = 0.0f;
  const FlipMap m = flip_srgb(ref, flat(w, h, 1, 1, 1), w, h);
  const float* row = &m.error[size_t(4) * w];
  for (int x = 0; x <= 20; ++x) EXPECT_NEAR(row[x], 0.967380, 2e-5) << x;
  for (int x = 25; x <= 30; ++x) {
    EXPECT_GT(row[x], 0.967380 + 0.005) << x;
    EXPECT_GT(row[x], row[x - 1]) << x;  // growing toward the edge
  }
  for (int x = 32; x <= 34; ++x) EXPECT_GT(row[x], 0.25) << x;  // white side, near the edge
  for (int x = 43; x < w; ++x) EXPECT_NEAR(row[x], 0.0, 1e-6) << x;
}

TEST(Flip, IsSymmetric) {
  // HyAB and the absolute feature difference are symmetric, so FLIP is too.
  const std::vector<float> a = random_srgb(20, 18, 2), b = random_srgb(20, 18, 3);
  const FlipMap ab = flip_srgb(a, b, 20, 18), ba = flip_srgb(b, a, 20, 18);
  for (size_t i = 0; i < ab.error.size(); ++i) ASSERT_NEAR(ab.error[i], ba.error[i], 1e-6) << i;
  EXPECT_GT(ab.mean, 0.05);
}

TEST(Flip, GrowsWithTheDifference) {
  // Lightness difference and the remapping are monotone, so a grey moving away from the
  // reference's grey scores higher at every step.
  double last = 0.0;
  for (float v = 0.55f; v <= 1.0f; v += 0.05f) {
    const double mean =
        flip_srgb(flat(12, 12, 0.5f, 0.5f, 0.5f), flat(12, 12, v, v, v), 12, 12).mean;
    EXPECT_GT(mean, last) << v;
    last = mean;
  }
}

TEST(Flip, KernelsAreNormalisedAsThePaperSays) {
  int r = 0;
  for (FlipChannel c :
       {FlipChannel::kAchromatic, FlipChannel::kRedGreen, FlipChannel::kBlueYellow}) {
    const std::vector<double> k = flip_csf_kernel(c, kFlipDefaultPpd, &r);
    // r = ceil(3 sqrt(0.04 / (2 pi^2)) 67.02) = ceil(9.05) = 10.
    EXPECT_EQ(r, 10);
    double sum = 0.0;
    for (double v : k) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  for (bool point : {false, true}) {
    const std::vector<double> k = flip_feature_kernel(point, kFlipDefaultPpd, &r);
    // sigma = 0.5 * 0.082 * 67.02 = 2.748; r = ceil(3 sigma) = 9.
    EXPECT_EQ(r, 9);
    double positive = 0.0, negative = 0.0;
    for (double v : k) (v > 0 ? positive : negative) += v;
    EXPECT_NEAR(positive, 1.0, 1e-12);
    EXPECT_NEAR(negative, -1.0, 1e-12);
  }
}

TEST(Flip, ImagesAreComparedAsDisplayed) {
  // Linear radiance above 1 clamps like the PNG does: 2.0 and 1.0 look the same.
  const FlipMap same = flip_map(Image(12, 12, vec3(2.0f)), Image(12, 12, vec3(1.0f)));
  EXPECT_EQ(same.mean, 0.0);
  const FlipMap m = flip_map(Image(12, 12, vec3(0.0f)), Image(12, 12, vec3(1.0f)));
  EXPECT_NEAR(m.mean, 0.967380, 2e-5);
  EXPECT_THROW(flip_map(Image(12, 12), Image(12, 11)), Error);
  EXPECT_THROW(flip_map(Image(4, 4), Image(4, 4), 0.0), Error);
  EXPECT_THROW(flip_map(Image(4, 4), Image(4, 4), std::nan("")), Error);
}

TEST(Flip, GreyMapIsTheErrorInEightBits) {
  FlipMap m;
  m.width = 3;
  m.height = 1;
  m.error = {0.0f, 0.5f, 1.0f};
  const std::vector<uint8_t> rgb = flip_grey_rgb8(m);
  const std::vector<uint8_t> expected = {0, 0, 0, 128, 128, 128, 255, 255, 255};
  EXPECT_EQ(rgb, expected);
}

}  // namespace
}  // namespace bounce
