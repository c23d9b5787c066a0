// The environment map: its files (.hdr, .exr) and their errors, and its sampling distribution
// checked by brute force on small synthetic maps: the pdf integrates to 1 over the sphere, is
// proportional to luminance, is what the sampler draws with, and estimates irradiance right.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "bounce/core/color.h"
#include "bounce/core/image_io.h"
#include "bounce/scene/environment_map.h"
#include "environment_test_util.h"
#include "scene_test_util.h"

namespace bounce {
namespace {

using scene_test::contains;
using scene_test::error_of;
using scene_test::hdr_file;
using scene_test::synthetic_map;
using scene_test::TempDir;

LightRecord environment_light(float rotation_deg) {
  return Light::environment(vec3(1.0f), rotation_deg);
}

// The integral over the sphere of f(world direction), by the midpoint rule on an n x n/2 grid
// in world latitude-longitude (d(omega) = sin(theta) d(theta) d(phi)).
template <typename F>
double sphere_integral(int n, F&& f) {
  const int m = n / 2;
  double sum = 0.0;
  for (int j = 0; j < m; ++j) {
    const double theta = kPi * (j + 0.5) / m;
    const double weight = std::sin(theta) * (kPi / m) * (2.0 * kPi / n);
    for (int i = 0; i < n; ++i) {
      const double phi = 2.0 * kPi * (i + 0.5) / n;
      const vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                   float(std::sin(theta) * std::sin(phi)));
      sum += f(d) * weight;
    }
  }
  return sum;
}

// RGBE keeps 8 bits of mantissa: decoded values are within half a step (1/256 relative) of
// what was written, flat or run-length encoded.
void expect_rgbe_near(const Image& back, const Image& image) {
  ASSERT_EQ(back.width(), image.width());
  ASSERT_EQ(back.height(), image.height());
  for (size_t i = 0; i < image.pixel_count(); ++i) {
    const vec3 want = image.pixels()[i];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back.pixels()[i][c], want[c], max_component(want) / 128.0f) << i;
  }
}

TEST(EnvironmentMap, HdrFileRoundTrip) {
  TempDir dir;
  Image image(3, 2);
  const vec3 values[6] = {{1, 0.5f, 0.25f}, {2, 2, 2},    {0, 0, 0},
                          {3, 1.5f, 0.75f}, {0.5f, 4, 1}, {8, 8, 16}};
  for (int i = 0; i < 6; ++i) image.at(i % 3, i / 3) = values[i];
  const std::string flat = dir.write("flat.hdr", hdr_file(image));
  expect_rgbe_near(load_image(flat), image);
  EXPECT_EQ(load_image(flat).at(2, 0), vec3(0.0f));  // exponent 0 is black
  const Image wide = synthetic_map(40, 6);           // run-length encoded, with runs
  const std::string rle = dir.write("rle.hdr", hdr_file(wide));
  expect_rgbe_near(load_image(rle), wide);
  const EnvironmentMap map = EnvironmentMap::load(rle);
  EXPECT_EQ(map.width(), 40);
  EXPECT_NEAR(map.max_value(), 40.0f, 40.0f / 128.0f);
}

TEST(EnvironmentMap, ExrFileLoads) {
  TempDir dir;
  const Image image = synthetic_map(8, 4);
  const std::string path = dir.file("sky.exr");
  save_image(path, image);
  const EnvironmentMap map = EnvironmentMap::load(path);
  ASSERT_EQ(map.width(), 8);
  ASSERT_EQ(map.height(), 4);
  EXPECT_EQ(map.view().texels[9], image.pixels()[9]);
}

TEST(EnvironmentMap, MalformedFilesAreClearErrors) {
  TempDir dir;
  const std::string good = hdr_file(synthetic_map(4, 2));
  struct Case {
    const char* name;
    std::string bytes;
    const char* says;
  };
  std::string overrun = hdr_file(synthetic_map(8, 2));
  overrun[overrun.find("+X 8\n") + 9] = char(128 + 100);  // the first run: 100 of 8 pixels
  const Case cases[] = {
      {"no_signature.hdr", "P6\n4 2\n255\n" + std::string(24, 'x'), "not a Radiance .hdr file"},
      {"empty.hdr", "", "the file is empty"},
      {"truncated.hdr", good.substr(0, good.size() - 10), "truncated in scanline 1"},
      {"no_end.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "header has no end"},
      {"bad_size.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y x +X 4\n", "resolution line"},
      {"huge.hdr", "#?RADIANCE\n\n-Y 99999 +X 99999\nxx", "invalid image size"},
      {"bad_format.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n",
       "unsupported pixel format"},
      {"overrun.hdr", overrun, "past its 8 pixels"},
      {"garbage.exr", std::string("v/1\x01garbage that is not an OpenEXR file"), "garbage.exr"},
      {"sky.png", "not an image at all", "must be an .exr or .hdr"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write(c.name, c.bytes);
    const std::string message = error_of([&] { EnvironmentMap::load(path); });
    EXPECT_TRUE(contains(message, path)) << c.name << ": " << message;
    EXPECT_TRUE(contains(message, c.says)) << c.name << ": " << message;
  }
  EXPECT_TRUE(
      contains(error_of([&] { EnvironmentMap::load(dir.file("missing.hdr")); }), "missing.hdr"));
}

TEST(EnvironmentMap, NegativeOrNonFiniteTexelsAreRefused) {
  Image image = synthetic_map(4, 2);
  image.at(2, 1) = vec3(1.0f, -0.5f, 1.0f);
  EXPECT_TRUE(contains(error_of([&] { EnvironmentMap::from_image(image, "neg.exr"); }),
                       "neg.exr: environment map texel (2, 1)"));
  image.at(2, 1) = vec3(std::nanf(""));
  EXPECT_TRUE(
      contains(error_of([&] { EnvironmentMap::from_image(image, "nan.exr"); }), "not finite"));
}

TEST(EnvironmentMap, PdfIntegratesToOneOverTheSphere) {
  const EnvironmentMap map = EnvironmentMap::from_image(synthetic_map(16, 8), "synthetic");
  for (float rotation : {0.0f, 37.0f}) {
    const LightRecord light = environment_light(rotation);
    const double integral = sphere_integral(
        1024, [&](vec3 d) { return double(environment_pdf(light, map.view(), d)); });
    EXPECT_NEAR(integral, 1.0, 5e-3) << "rotation " << rotation;
  }
  // A sky colour: uniform over the sphere.
  const LightRecord sky = environment_light(0.0f);
  EXPECT_NEAR(sphere_integral(64, [&](vec3 d) { return environment_pdf(sky, {}, d); }), 1.0, 1e-3);
}

TEST(EnvironmentMap, PdfIsProportionalToLuminance) {
  const Image image = synthetic_map(16, 8);
  const EnvironmentMap map = EnvironmentMap::from_image(image, "synthetic");
  const LightRecord light = environment_light(-70.0f);
  // At each texel's centre (where sin(theta) is the row's), pdf / luminance is one constant.
  double ratio = -1.0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const vec2 uv((x + 0.5f) / 16.0f, (y + 0.5f) / 8.0f);
      const vec3 d = environment_from_map(light.rotation, environment_direction(uv));
      const float pdf = environment_pdf(light, map.view(), d);
      const float lum = luminance(image.at(x, y));
      EXPECT_EQ(environment_radiance(light, map.view(), d), image.at(x, y)) << x << ", " << y;
      if (lum == 0.0f) {
        EXPECT_EQ(pdf, 0.0f) << x << ", " << y;
        continue;
      }
      if (ratio < 0.0) ratio = pdf / lum;
      EXPECT_NEAR(pdf / lum, ratio, 1e-4 * ratio) << x << ", " << y;
    }
}

TEST(EnvironmentMap, SamplesCarryThePdfAndRadianceOfTheirDirection) {
  const Image image = synthetic_map(16, 8);
  const EnvironmentMap map = EnvironmentMap::from_image(image, "synthetic");
  const LightRecord light = environment_light(120.0f);
  std::vector<double> hits(16 * 8, 0.0);
  const int n = 200000;
  Pcg32 rng(3, 5);
  int mismatched = 0, invalid = 0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample s = sample_environment(light, map.view(), rng.next2());
    if (!(s.pdf > 0.0f)) {  // only exactly at a pole, where sin(theta) = 0
      ++invalid;
      continue;
    }
    EXPECT_NEAR(glm::length(s.direction), 1.0f, 1e-5f);
    const float pdf = environment_pdf(light, map.view(), s.direction);
    // A direction exactly on a texel border may round into the neighbour: rare.
    if (std::abs(pdf - s.pdf) > 1e-3f * s.pdf ||
        environment_radiance(light, map.view(), s.direction) != s.radiance)
      ++mismatched;
    const vec2 uv = environment_uv(environment_to_map(light.rotation, s.direction));
    const ivec2 t = environment_texel(map.view(), uv);
    hits[size_t(t.y) * 16 + size_t(t.x)] += 1.0;
  }
  EXPECT_LT(mismatched, n / 1000);
  EXPECT_LT(invalid, 3);
  // Each texel is drawn with its probability (within 4 standard deviations).
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const double p = environment_texel_probability(map.view(), x, y);
      const double sigma = std::sqrt(n * p * (1.0 - p));
      EXPECT_NEAR(hits[size_t(y) * 16 + size_t(x)], n * p, 4.0 * sigma + 1.0) << x << ", " << y;
    }
}

TEST(EnvironmentMap, MeanIsTheSphereAverage) {
  const EnvironmentMap map = EnvironmentMap::from_image(synthetic_map(16, 8), "synthetic");
  const LightRecord light = environment_light(0.0f);
  for (int c = 0; c < 3; ++c) {
    const double brute =
        sphere_integral(
            2048, [&](vec3 d) { return double(environment_radiance(light, map.view(), d)[c]); }) /
        (4.0 * kPi);
    EXPECT_NEAR(map.mean()[c], brute, 5e-3 * brute) << c;
  }
}

// Irradiance on a surface by importance-sampling the map equals the brute-force integral of
// L cos over the hemisphere: the estimator direct light and the path tracer use.
TEST(EnvironmentMap, SampledIrradianceEqualsBruteForce) {
  const EnvironmentMap map = EnvironmentMap::from_image(synthetic_map(16, 8), "synthetic");
  const LightRecord light = environment_light(25.0f);
  for (const vec3 n : {vec3(0, 1, 0), glm::normalize(vec3(0.6f, 0.3f, -0.7f))}) {
    for (int c = 0; c < 3; ++c) {
      const double brute = sphere_integral(2048, [&](vec3 d) {
        return double(environment_radiance(light, map.view(), d)[c]) *
               std::max(0.0f, glm::dot(n, d));
      });
      double sum = 0.0;
      const int samples = 400000;
      Pcg32 rng(11, uint32_t(c));
      for (int k = 0; k < samples; ++k) {
        const EnvironmentSample s = sample_environment(light, map.view(), rng.next2());
        if (!(s.pdf > 0.0f)) continue;  // a pole: contributes nothing
        sum += double(s.radiance[c]) * std::max(0.0f, glm::dot(n, s.direction)) / s.pdf;
      }
      EXPECT_NEAR(sum / samples, brute, 0.01 * brute) << "channel " << c;
    }
  }
}

TEST(EnvironmentMap, RotationTurnsTheMapAboutUp) {
  const EnvironmentMap map = EnvironmentMap::from_image(synthetic_map(16, 8), "synthetic");
  const LightRecord turned = environment_light(90.0f), still = environment_light(0.0f);
  // The map's centre column faces -z; turned by 90 degrees (+x towards -z, so -z towards -x) it
  // faces -x.
  const vec3 centre = environment_direction(vec2(0.5f, 0.3f));
  EXPECT_NEAR(centre.z, -std::sin(0.3f * kPi), 1e-5f);
  const vec3 moved = environment_from_map(turned.rotation, centre);
  EXPECT_NEAR(moved.x, -std::sin(0.3f * kPi), 1e-5f);
  EXPECT_EQ(environment_radiance(turned, map.view(), moved),
            environment_radiance(still, map.view(), centre));
}

}  // namespace
}  // namespace bounce
