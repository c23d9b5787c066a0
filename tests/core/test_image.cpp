#include "bounce/core/image.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "bounce/core/color.h"
#include "bounce/core/error.h"

namespace bounce {
namespace {

// An image whose pixel (x, y) is (x, y, 10x + y), so that any row/column mixup shows.
Image coordinate_image(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image.at(x, y) = vec3(x, y, 10 * x + y);
  }
  return image;
}

void expect_vec3_near(vec3 actual, vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Checks that f throws bounce::Error whose message contains the given text.
template <typename F>
void expect_error_containing(F f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "expected bounce::Error containing '" << text << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(Color, SrgbKnownValues) {
  EXPECT_NEAR(srgb_encode(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(srgb_decode(0.5f), 0.214041f, 1e-5f);
  EXPECT_FLOAT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_NEAR(srgb_encode(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(srgb_decode(1.0f), 1.0f, 1e-6f);
  // The linear segment near black.
  EXPECT_NEAR(srgb_encode(0.001f), 0.01292f, 1e-7f);
  EXPECT_NEAR(srgb_decode(0.02f), 0.02f / 12.92f, 1e-8f);
}

TEST(Color, SrgbIsContinuousAtTheSegmentJoin) {
  EXPECT_NEAR(srgb_encode(0.0031308f), srgb_encode(0.0031309f), 1e-5f);
  EXPECT_NEAR(srgb_decode(0.04045f), srgb_decode(0.04046f), 1e-5f);
}

TEST(Color, SrgbRoundTrip) {
  for (int i = 0; i <= 1000; ++i) {
    const float x = float(i) / 1000.0f;
    EXPECT_NEAR(srgb_decode(srgb_encode(x)), x, 1e-5f * (1.0f + x)) << x;
    EXPECT_NEAR(srgb_encode(srgb_decode(x)), x, 1e-5f * (1.0f + x)) << x;
  }
}

TEST(Color, Srgb8FromLinear) {
  EXPECT_EQ(srgb8_from_linear(0.0f, 1.0f), 0);
  EXPECT_EQ(srgb8_from_linear(1.0f, 1.0f), 255);
  EXPECT_EQ(srgb8_from_linear(0.18f, 1.0f), 118);   // 255 * 0.46136 = 117.65
  EXPECT_EQ(srgb8_from_linear(0.5f, 1.0f), 188);    // 255 * 0.73536 = 187.52
  EXPECT_EQ(srgb8_from_linear(0.125f, 2.0f), 137);  // scale first: 0.25 -> 136.96
  // Clamped outside [0, 1]; NaN shows as black.
  EXPECT_EQ(srgb8_from_linear(7.0f, 1.0f), 255);
  EXPECT_EQ(srgb8_from_linear(0.6f, 2.0f), 255);
  EXPECT_EQ(srgb8_from_linear(-1.0f, 1.0f), 0);
  EXPECT_EQ(srgb8_from_linear(std::numeric_limits<float>::infinity(), 1.0f), 255);
  EXPECT_EQ(srgb8_from_linear(std::numeric_limits<float>::quiet_NaN(), 1.0f), 0);
}

TEST(Color, LuminanceOfPrimaries) {
  EXPECT_FLOAT_EQ(luminance(vec3(1, 0, 0)), 0.2126f);
  EXPECT_FLOAT_EQ(luminance(vec3(0, 1, 0)), 0.7152f);
  EXPECT_FLOAT_EQ(luminance(vec3(0, 0, 1)), 0.0722f);
  EXPECT_NEAR(luminance(vec3(1, 1, 1)), 1.0f, 1e-6f);
  EXPECT_NEAR(luminance(vec3(2, 4, 8)), 2 * 0.2126f + 4 * 0.7152f + 8 * 0.0722f, 1e-5f);
}

TEST(Image, ConstructionAndRowMajorLayout) {
  const Image empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.width(), 0);

  Image image(3, 2, vec3(0.5f, 1.0f, 2.0f));
  EXPECT_EQ(image.width(), 3);
  EXPECT_EQ(image.height(), 2);
  EXPECT_EQ(image.pixel_count(), 6u);
  EXPECT_FALSE(image.empty());
  EXPECT_EQ(image.at(2, 1), vec3(0.5f, 1.0f, 2.0f));
  image.at(2, 0) = vec3(7.0f);
  EXPECT_EQ(image.pixels()[2], vec3(7.0f));
  image.at(0, 1) = vec3(9.0f);
  EXPECT_EQ(image.data()[3], vec3(9.0f));
}

TEST(Image, NegativeSizeThrows) {
  EXPECT_THROW(Image(-1, 4), Error);
  EXPECT_THROW(Image(4, -1), Error);
}

TEST(Image, ElementwiseArithmetic) {
  const Image a = coordinate_image(4, 3);
  const Image b(4, 3, vec3(1.0f, 2.0f, 3.0f));

  const Image sum = a + b;
  EXPECT_EQ(sum.at(3, 1), vec3(4.0f, 3.0f, 34.0f));
  const Image difference = a - b;
  EXPECT_EQ(difference.at(3, 1), vec3(2.0f, -1.0f, 28.0f));
  const Image product = a * b;
  EXPECT_EQ(product.at(3, 1), vec3(3.0f, 2.0f, 93.0f));
  const Image scaled = a * 0.5f;
  EXPECT_EQ(scaled.at(3, 2), vec3(1.5f, 1.0f, 16.0f));
  const Image distance = abs_diff(b, a);
  EXPECT_EQ(distance.at(3, 1), vec3(2.0f, 1.0f, 28.0f));
  EXPECT_EQ(distance.at(0, 0), vec3(1.0f, 2.0f, 3.0f));

  Image accumulated = a;
  accumulated += b;
  accumulated += b;
  EXPECT_EQ(accumulated.at(2, 2), vec3(4.0f, 6.0f, 28.0f));
  accumulated *= 2.0f;
  EXPECT_EQ(accumulated.at(2, 2), vec3(8.0f, 12.0f, 56.0f));
  // The operands are untouched.
  EXPECT_EQ(a.at(2, 2), vec3(2.0f, 2.0f, 22.0f));
}

TEST(Image, SizeMismatchThrows) {
  const Image a(2, 3);
  const Image b(3, 2);
  const std::string message = "image sizes differ: 2x3 vs 3x2";
  expect_error_containing([&] { (void)(a + b); }, message);
  expect_error_containing([&] { (void)(a - b); }, message);
  expect_error_containing([&] { (void)(a * b); }, message);
  expect_error_containing([&] { (void)abs_diff(a, b); }, message);
  Image c = a;
  expect_error_containing([&] { c += b; }, message);
}

TEST(Image, MeanOverWholeImageAndRectangle) {
  const Image image = coordinate_image(4, 3);
  // x runs over 0..3 (mean 1.5), y over 0..2 (mean 1).
  expect_vec3_near(mean(image), vec3(1.5f, 1.0f, 16.0f), 1e-6f);
  // [1, 3) x [0, 2): x in {1, 2}, y in {0, 1}.
  expect_vec3_near(mean(image, 1, 0, 3, 2), vec3(1.5f, 0.5f, 15.5f), 1e-6f);
  // A single pixel.
  expect_vec3_near(mean(image, 3, 2, 4, 3), vec3(3.0f, 2.0f, 32.0f), 0.0f);
}

TEST(Image, MeanRejectsBadRectangles) {
  const Image image(4, 3);
  EXPECT_THROW(mean(image, 1, 1, 1, 2), Error);   // empty in x
  EXPECT_THROW(mean(image, 1, 2, 2, 2), Error);   // empty in y
  EXPECT_THROW(mean(image, 2, 0, 1, 3), Error);   // inverted
  EXPECT_THROW(mean(image, -1, 0, 2, 2), Error);  // left of the image
  EXPECT_THROW(mean(image, 0, 0, 5, 3), Error);   // right of the image
  EXPECT_THROW(mean(image, 0, 0, 4, 4), Error);   // below the image
  EXPECT_THROW(mean(Image()), Error);             // no pixels at all
}

TEST(Image, LuminancePerPixel) {
  Image image(3, 2);
  image.at(1, 0) = vec3(1, 0, 0);
  image.at(2, 1) = vec3(0, 0, 2);
  const std::vector<float> values = luminance(image);
  ASSERT_EQ(values.size(), 6u);
  EXPECT_FLOAT_EQ(values[1], 0.2126f);
  EXPECT_FLOAT_EQ(values[5], 0.1444f);
  EXPECT_FLOAT_EQ(values[0], 0.0f);
}

}  // namespace
}  // namespace bounce
