// LDR-FLIP after Andersson et al., HPG 2020 (section numbers below are the paper's). Our own
// code from the paper's formulas; the constants are the paper's.
#include "bounce/metrics/flip.h"

#include <algorithm>
#include <cmath>

#include "bounce/core/color.h"
#include "bounce/core/device.h"
#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/metrics/image_metrics.h"

namespace bounce {

namespace {

constexpr double kPiDouble = 3.14159265358979323846;

// Exponents on the colour and feature errors, and the colour remapping's knee (section 4).
constexpr double kQc = 0.7, kQf = 0.5, kPc = 0.4, kPt = 0.95;
// Peak-to-trough width of the edge detector, in degrees (section 5.2).
constexpr double kFeatureWidthDeg = 0.082;

// The contrast sensitivity functions as sums of two Gaussians per opponent channel, from
// Johnson and Fairchild's fit as the paper uses it (section 5.1): a1, b1, a2, b2.
struct CsfGaussians {
  double a1, b1, a2, b2;
};
constexpr CsfGaussians kCsf[3] = {
    {1.0, 0.0047, 0.0, 1e-5},      // achromatic (a2 = 0; b2 only avoids a division by zero)
    {1.0, 0.0053, 0.0, 1e-5},      // red-green
    {34.1, 0.04, 13.5, 0.025}};    // blue-yellow
constexpr double kCsfMaxB = 0.04;  // the widest Gaussian sets one radius for all three

// Linear sRGB (D65) to CIE XYZ, the exact rational form of the sRGB matrix.
struct Vec3d {
  double x, y, z;
};
BOUNCE_HD inline Vec3d xyz_from_linear(double r, double g, double b) {
  return {(10135552.0 * r + 8788810.0 * g + 4435075.0 * b) / 24577794.0,
          (2613072.0 * r + 8788810.0 * g + 887015.0 * b) / 12288897.0,
          (1425312.0 * r + 8788810.0 * g + 70074185.0 * b) / 73733382.0};
}
// The white the opponent and L*a*b* spaces are relative to: XYZ of linear (1, 1, 1).
BOUNCE_HD inline Vec3d white_xyz() {
  return xyz_from_linear(1.0, 1.0, 1.0);
}

// The inverse of xyz_from_linear (by Cramer's rule, so it is the exact inverse in double).
BOUNCE_HD inline Vec3d linear_from_xyz(const Vec3d& v) {
  const double m[3][3] = {
      {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
      {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
      {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  const double i[3][3] = {
      {c00, m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][1] * m[1][2] - m[0][2] * m[1][1]},
      {c01, m[0][0] * m[2][2] - m[0][2] * m[2][0], m[0][2] * m[1][0] - m[0][0] * m[1][2]},
      {c02, m[0][1] * m[2][0] - m[0][0] * m[2][1], m[0][0] * m[1][1] - m[0][1] * m[1][0]}};
  return {(i[0][0] * v.x + i[0][1] * v.y + i[0][2] * v.z) / det,
          (i[1][0] * v.x + i[1][1] * v.y + i[1][2] * v.z) / det,
          (i[2][0] * v.x + i[2][1] * v.y + i[2][2] * v.z) / det};
}

// YCxCz (section 5.1): the linear opponent space the filters work in, relative to the white.
BOUNCE_HD inline Vec3d ycxcz_from_xyz(const Vec3d& v) {
  const Vec3d w = white_xyz();
  const double x = v.x / w.x, y = v.y / w.y, z = v.z / w.z;
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}
BOUNCE_HD inline Vec3d xyz_from_ycxcz(const Vec3d& v) {
  const Vec3d w = white_xyz();
  const double y = (v.x + 16.0) / 116.0;
  return {(y + v.y / 500.0) * w.x, y * w.y, (y - v.z / 200.0) * w.z};
}

// CIE L*a*b* relative to the same white, then the Hunt adjustment (a and b scaled by L/100,
// so that dark colours differ less in chroma: section 5.1).
BOUNCE_HD inline double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}
BOUNCE_HD inline Vec3d hunt_lab_from_linear(double r, double g, double b) {
  const Vec3d v = xyz_from_linear(r, g, b), w = white_xyz();
  const double fx = lab_f(v.x / w.x), fy = lab_f(v.y / w.y), fz = lab_f(v.z / w.z);
  const double l = 116.0 * fy - 16.0;
  return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

// HyAB (Abasi et al. 2020): city-block lightness plus Euclidean chroma distance.
BOUNCE_HD inline double hyab(const Vec3d& p, const Vec3d& q) {
  const double da = p.y - q.y, db = p.z - q.z;
  return std::fabs(p.x - q.x) + std::sqrt(da * da + db * db);
}

// The largest colour difference FLIP expects, green against blue, raised to qc.
double cmax() {
  return std::pow(hyab(hunt_lab_from_linear(0, 1, 0), hunt_lab_from_linear(0, 0, 1)), kQc);
}

BOUNCE_HD inline double remap_color_error(double hyab_distance, double c_max) {
  const double e = std::pow(hyab_distance, kQc);
  const double knee = kPc * c_max;
  return e < knee ? (kPt / knee) * e : kPt + (e - knee) / (c_max - knee) * (1.0 - kPt);
}

// What the per-pixel bodies read: one image's opponent planes and the filters.
struct FlipImageView {
  const float* planes[3];  // Y, Cx, Cz (YCxCz)
  int width, height;
  const double* csf[3];  // (2 csf_radius + 1)^2 taps each
  int csf_radius;
  const double* edge;  // x-direction detectors, (2 feature_radius + 1)^2 taps
  const double* point;
  int feature_radius;
};

// What FLIP compares per pixel: the filtered colour in Hunt-adjusted L*a*b* and the edge and
// point response magnitudes. Both images go through the same body, so identical images give
// identical records (and exactly 0), whatever the compiler does with floating point.
struct FlipPixel {
  double l, a, b, edge, point;
};

// Correlates a plane with a square kernel at (x, y), with the border pixels replicated outward;
// `transposed` reads the kernel as its transpose (the y-direction detectors).
BOUNCE_HD inline double correlate(const float* plane, int w, int h, const double* k, int r, int x,
                                  int y, bool transposed = false) {
  const int side = 2 * r + 1;
  double s = 0.0;
  for (int dy = -r; dy <= r; ++dy) {
    const int yy = std::clamp(y + dy, 0, h - 1);
    for (int dx = -r; dx <= r; ++dx) {
      const int xx = std::clamp(x + dx, 0, w - 1);
      const double weight =
          transposed ? k[(dx + r) * side + (dy + r)] : k[(dy + r) * side + (dx + r)];
      s += weight * double(plane[size_t(yy) * w + xx]);
    }
  }
  return s;
}

BOUNCE_HD inline FlipPixel flip_image_pixel(const FlipImageView& v, int x, int y) {
  // Colour pipeline (section 5.1): the filtered opponent colour back to linear RGB, clamped to
  // the unit cube, then Hunt-adjusted L*a*b*.
  Vec3d o;
  o.x = correlate(v.planes[0], v.width, v.height, v.csf[0], v.csf_radius, x, y);
  o.y = correlate(v.planes[1], v.width, v.height, v.csf[1], v.csf_radius, x, y);
  o.z = correlate(v.planes[2], v.width, v.height, v.csf[2], v.csf_radius, x, y);
  const Vec3d rgb = linear_from_xyz(xyz_from_ycxcz(o));
  const Vec3d lab = hunt_lab_from_linear(std::clamp(rgb.x, 0.0, 1.0), std::clamp(rgb.y, 0.0, 1.0),
                                         std::clamp(rgb.z, 0.0, 1.0));
  // Feature pipeline (section 5.2) on the achromatic channel normalised to [0, 1],
  // (Y + 16) / 116: the detectors are linear and their taps sum to 0, so filtering Y and
  // dividing by 116 is the same.
  const int r = v.feature_radius;
  const float* y_plane = v.planes[0];
  const double ex = correlate(y_plane, v.width, v.height, v.edge, r, x, y) / 116.0;
  const double ey = correlate(y_plane, v.width, v.height, v.edge, r, x, y, true) / 116.0;
  const double px = correlate(y_plane, v.width, v.height, v.point, r, x, y) / 116.0;
  const double py = correlate(y_plane, v.width, v.height, v.point, r, x, y, true) / 116.0;
  return {lab.x, lab.y, lab.z, std::sqrt(ex * ex + ey * ey), std::sqrt(px * px + py * py)};
}

// FLIP at one pixel: colour error raised to (1 - feature error) (section 4).
BOUNCE_HD inline float flip_combine(const FlipPixel& p, const FlipPixel& q, double c_max) {
  const double color = remap_color_error(hyab({p.l, p.a, p.b}, {q.l, q.a, q.b}), c_max);
  const double difference = std::max(std::fabs(p.edge - q.edge), std::fabs(p.point - q.point));
  const double feature = std::pow(difference / std::sqrt(2.0), kQf);
  return float(std::pow(color, 1.0 - feature));
}

// sRGB-encoded [0, 1] values to YCxCz planes.
void opponent_planes(const std::vector<float>& srgb, size_t n, std::vector<float> planes[3]) {
  for (int c = 0; c < 3; ++c) planes[c].resize(n);
  parallel_for(n, [&](size_t i) {
    const Vec3d o = ycxcz_from_xyz(xyz_from_linear(
        srgb_decode(srgb[3 * i]), srgb_decode(srgb[3 * i + 1]), srgb_decode(srgb[3 * i + 2])));
    planes[0][i] = float(o.x);
    planes[1][i] = float(o.y);
    planes[2][i] = float(o.z);
  });
}

void check_ppd(double ppd) {
  if (!std::isfinite(ppd) || ppd <= 0.0)
    fail("FLIP: pixels per degree must be a positive number, got {}", ppd);
  if (ppd > 10000.0) fail("FLIP: {} pixels per degree is beyond any display (at most 10000)", ppd);
}

}  // namespace

std::vector<double> flip_csf_kernel(FlipChannel channel, double ppd, int* radius) {
  check_ppd(ppd);
  const CsfGaussians& g = kCsf[int(channel)];
  const int r = int(std::ceil(3.0 * std::sqrt(kCsfMaxB / (2.0 * kPiDouble * kPiDouble)) * ppd));
  const int side = 2 * r + 1;
  std::vector<double> k(size_t(side) * side);
  double sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      const double d2 = (double(x) * x + double(y) * y) / (ppd * ppd);  // squared degrees
      const double s =
          g.a1 * std::sqrt(kPiDouble / g.b1) * std::exp(-kPiDouble * kPiDouble * d2 / g.b1) +
          g.a2 * std::sqrt(kPiDouble / g.b2) * std::exp(-kPiDouble * kPiDouble * d2 / g.b2);
      k[size_t(y + r) * side + (x + r)] = s;
      sum += s;
    }
  for (double& s : k) s /= sum;
  if (radius) *radius = r;
  return k;
}

std::vector<double> flip_feature_kernel(bool point, double ppd, int* radius) {
  check_ppd(ppd);
  const double sd = 0.5 * kFeatureWidthDeg * ppd;
  const int r = int(std::ceil(3.0 * sd));
  const int side = 2 * r + 1;
  std::vector<double> k(size_t(side) * side);
  double positive = 0.0, negative = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      const double g = std::exp(-(double(x) * x + double(y) * y) / (2.0 * sd * sd));
      const double v = point ? (double(x) * x / (sd * sd) - 1.0) * g : -double(x) * g;
      k[size_t(y + r) * side + (x + r)] = v;
      (v > 0.0 ? positive : negative) += v;
    }
  // Positive taps sum to 1 and negative ones to -1, so a flat image gives no response.
  for (double& v : k) v = v > 0.0 ? v / positive : (v < 0.0 ? v / -negative : 0.0);
  if (radius) *radius = r;
  return k;
}

double flip_color_error(double hyab_distance) {
  return remap_color_error(hyab_distance, cmax());
}

FlipMap flip_srgb(const std::vector<float>& reference, const std::vector<float>& test, int width,
                  int height, double ppd) {
  check_ppd(ppd);
  if (width <= 0 || height <= 0) fail("FLIP: image size {}x{} is empty", width, height);
  const size_t n = size_t(width) * size_t(height);
  if (reference.size() != 3 * n || test.size() != 3 * n)
    fail("FLIP: {} and {} values for a {}x{} image (3 per pixel)", reference.size(), test.size(),
         width, height);
  std::vector<double> csf[3];
  int csf_radius = 0, feature_radius = 0;
  for (int c = 0; c < 3; ++c) csf[c] = flip_csf_kernel(FlipChannel(c), ppd, &csf_radius);
  const std::vector<double> edge = flip_feature_kernel(false, ppd, &feature_radius);
  const std::vector<double> point = flip_feature_kernel(true, ppd, nullptr);

  // Each image through the same per-pixel body.
  const auto image_pixels = [&](const std::vector<float>& srgb) {
    std::vector<float> planes[3];
    opponent_planes(srgb, n, planes);
    FlipImageView v;
    for (int c = 0; c < 3; ++c) {
      v.planes[c] = planes[c].data();
      v.csf[c] = csf[c].data();
    }
    v.width = width;
    v.height = height;
    v.csf_radius = csf_radius;
    v.edge = edge.data();
    v.point = point.data();
    v.feature_radius = feature_radius;
    std::vector<FlipPixel> out(n);
    FlipPixel* o = out.data();
    parallel_for_2d(width, height,
                    [&](int x, int y) { o[size_t(y) * width + x] = flip_image_pixel(v, x, y); });
    return out;
  };
  const std::vector<FlipPixel> ref = image_pixels(reference), tst = image_pixels(test);

  FlipMap map;
  map.width = width;
  map.height = height;
  map.ppd = ppd;
  map.error.resize(n);
  const double c_max = cmax();
  float* out = map.error.data();
  parallel_for(n, [&](size_t i) { out[i] = flip_combine(ref[i], tst[i], c_max); });
  double sum = 0.0;
  for (float e : map.error) sum += e;
  map.mean = sum / double(n);
  return map;
}

FlipMap flip_map(const Image& reference, const Image& test, double ppd) {
  if (reference.width() != test.width() || reference.height() != test.height())
    fail("cannot compare images of different sizes: the reference is {}x{}, the test {}x{}",
         reference.width(), reference.height(), test.width(), test.height());
  // What a viewer sees: the 8-bit sRGB values of the PNG, scaled to [0, 1].
  const auto displayed = [](const Image& image) {
    const std::vector<uint8_t> bytes = srgb8_values(image);
    std::vector<float> out(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i) out[i] = float(bytes[i]) / 255.0f;
    return out;
  };
  return flip_srgb(displayed(reference), displayed(test), reference.width(), reference.height(),
                   ppd);
}

std::vector<uint8_t> flip_grey_rgb8(const FlipMap& map) {
  std::vector<uint8_t> rgb(3 * map.error.size());
  for (size_t i = 0; i < map.error.size(); ++i) {
    const auto v = uint8_t(std::lround(255.0 * std::clamp(double(map.error[i]), 0.0, 1.0)));
    rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = v;
  }
  return rgb;
}

}  // namespace bounce
