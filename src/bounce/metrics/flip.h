// LDR-FLIP: the image difference of Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and
// Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020. It predicts what an
// observer flipping between two images notices: a colour difference after the eye's contrast
// sensitivity filters, raised where edges and points differ. Per pixel in [0, 1], 0 where the
// images agree.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/image.h"

namespace bounce {

// The paper's viewing setup: a 0.7 m wide 3840-pixel monitor seen from 0.7 m, i.e.
// 0.7 * 3840 / 0.7 * pi / 180 = 67.02 pixels per degree of visual angle.
inline constexpr double kFlipDefaultPpd = 3840.0 * 3.14159265358979323846 / 180.0;

struct FlipMap {
  int width = 0;
  int height = 0;
  std::vector<float> error;  // per pixel in [0, 1], row-major from the top
  double mean = 0.0;         // mean FLIP over the pixels: the one number reported
  double ppd = kFlipDefaultPpd;
};

// FLIP of `test` against `reference` as displayed: both through the PNG tone map at exposure 0
// (clamp to [0, 1], sRGB, 8 bits: the values srgb8_values() gives), seen at `ppd` pixels per
// degree. Throws Error when the sizes differ or ppd is not a positive finite number.
FlipMap flip_map(const Image& reference, const Image& test, double ppd = kFlipDefaultPpd);

// The same on sRGB-encoded values in [0, 1], 3 per pixel, row-major (the paper's input).
FlipMap flip_srgb(const std::vector<float>& reference, const std::vector<float>& test, int width,
                  int height, double ppd = kFlipDefaultPpd);

// The error map as an 8-bit grey PNG buffer (3 bytes per pixel): black is 0, white is 1.
std::vector<uint8_t> flip_grey_rgb8(const FlipMap& map);

// Building blocks, exposed for tests.

enum class FlipChannel { kAchromatic, kRedGreen, kBlueYellow };

// The contrast sensitivity filter of one opponent channel, (2r + 1)^2 taps summing to 1,
// row-major; r = ceil(3 sqrt(b_max / (2 pi^2)) ppd) is the same for the three channels.
std::vector<double> flip_csf_kernel(FlipChannel channel, double ppd, int* radius);

// The x-direction edge (first Gaussian derivative) or point (second derivative) detector,
// (2r + 1)^2 taps, positive taps summing to 1 and negative ones to -1; the y detector is its
// transpose. sigma = 0.5 * 0.082 degrees * ppd, r = ceil(3 sigma).
std::vector<double> flip_feature_kernel(bool point, double ppd, int* radius);

// Colour error from a HyAB distance in Hunt-adjusted L*a*b*: (distance^0.7) remapped to [0, 1]
// against cmax, the distance between green and blue raised to 0.7.
double flip_color_error(double hyab);

}  // namespace bounce
