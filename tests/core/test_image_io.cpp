#include "bounce/core/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bounce/core/color.h"
#include "bounce/core/error.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

// Each test gets its own empty directory, removed afterwards.
class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        fs::temp_directory_path() / fmt::format("bounce_image_io_{}_{}", ::getpid(), info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::vector<std::string> directory_entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }

  fs::path dir_;
};

Bytes read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void append_text(Bytes& bytes, const std::string& text) {
  bytes.insert(bytes.end(), text.begin(), text.end());
}

void append_float(Bytes& bytes, float value, bool little_endian) {
  unsigned char raw[4];
  std::memcpy(raw, &value, 4);  // the test host is little-endian (x86-64)
  if (little_endian) {
    bytes.insert(bytes.end(), raw, raw + 4);
  } else {
    bytes.insert(bytes.end(), {raw[3], raw[2], raw[1], raw[0]});
  }
}

// Checks that f throws bounce::Error whose message contains every given text.
template <typename F>
void expect_error_containing(F f, const std::vector<std::string>& texts) {
  try {
    f();
    ADD_FAILURE() << "expected bounce::Error";
  } catch (const Error& e) {
    for (const std::string& text : texts) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos)
          << "'" << e.what() << "' lacks '" << text << "'";
    }
  }
}

// Values an HDR renderer produces: zero, tiny, > 1, huge, negative, non-representable in 8 bits.
Image hdr_test_image(int width, int height) {
  Image image(width, height);
  const float specials[] = {0.0f, 1e-7f, 0.1f, 1.0f, 3.75f, 1234.5678f, 6.5e4f, -0.25f, 1e30f};
  int i = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x, i += 3) {
      image.at(x, y) = vec3(specials[i % 9], specials[(i + 1) % 9] * (1.0f + x),
                            specials[(i + 2) % 9] + 0.001f * y);
    }
  }
  image.at(width - 1, 0) = vec3(17.0f, 0.0f, 0.5f);  // a marker in the top-right corner
  return image;
}

void expect_images_identical(const Image& actual, const Image& expected) {
  ASSERT_EQ(actual.width(), expected.width());
  ASSERT_EQ(actual.height(), expected.height());
  for (int y = 0; y < expected.height(); ++y) {
    for (int x = 0; x < expected.width(); ++x) {
      EXPECT_EQ(actual.at(x, y), expected.at(x, y)) << "pixel " << x << ", " << y;
    }
  }
}

// A gradient in [0, 1] with a red marker at (width - 1, 1).
Image ldr_test_image(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at(x, y) =
          vec3(float(x) / width, float(y) / height, 0.5f * float(x + y) / (width + height));
    }
  }
  image.at(width - 1, 1) = vec3(1.0f, 0.0f, 0.0f);
  return image;
}

TEST_F(ImageIoTest, PngRoundTripWithinQuantisation) {
  const Image image = ldr_test_image(7, 4);
  save_image(path("a.png"), image);
  const Image loaded = load_image(path("a.png"));
  ASSERT_EQ(loaded.width(), 7);
  ASSERT_EQ(loaded.height(), 4);
  // Quantising the sRGB-encoded value to 8 bits moves it by at most half a step.
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 7; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(srgb_encode(loaded.at(x, y)[c]), srgb_encode(image.at(x, y)[c]),
                    0.5f / 255.0f + 1e-5f)
            << x << ", " << y << ", " << c;
      }
    }
  }
  EXPECT_EQ(loaded.at(6, 1), vec3(1.0f, 0.0f, 0.0f));
}

TEST_F(ImageIoTest, PngAppliesExposureClampAndNan) {
  Image image(3, 1);
  image.at(0, 0) = vec3(0.25f, 0.0f, 0.0f);
  image.at(1, 0) = vec3(5.0f, -1.0f, std::numeric_limits<float>::quiet_NaN());
  image.at(2, 0) = vec3(0.125f, 0.0625f, 0.0f);
  save_image(path("exposed.png"), image, 1.0f);
  const Image loaded = load_image(path("exposed.png"));
  // One stop brighter: 0.25 -> 0.5 and 0.125 -> 0.25, each up to 8-bit quantisation.
  EXPECT_NEAR(srgb_encode(loaded.at(0, 0).x), srgb_encode(0.5f), 0.5f / 255.0f);
  EXPECT_NEAR(srgb_encode(loaded.at(2, 0).x), srgb_encode(0.25f), 0.5f / 255.0f);
  EXPECT_NEAR(srgb_encode(loaded.at(2, 0).y), srgb_encode(0.125f), 0.5f / 255.0f);
  EXPECT_EQ(loaded.at(1, 0), vec3(1.0f, 0.0f, 0.0f));
}

TEST_F(ImageIoTest, SavePngRgb8StoresTheBytes) {
  // 3 x 2, top row first.
  const std::vector<uint8_t> rgb = {0,  0,   0,   255, 255, 255, 10, 20, 30,
                                    40, 128, 200, 1,   2,   3,   99, 0,  255};
  save_png_rgb8(path("rgb8.png"), 3, 2, rgb.data());
  const Image loaded = load_image(path("rgb8.png"));
  ASSERT_EQ(loaded.width(), 3);
  ASSERT_EQ(loaded.height(), 2);
  for (int i = 0; i < 6; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(loaded.at(i % 3, i / 3)[c], srgb_decode(rgb[3 * i + c] / 255.0f));
    }
  }
  EXPECT_THROW(save_png_rgb8(path("bad.png"), 0, 2, rgb.data()), Error);
  EXPECT_THROW(save_png_rgb8(path("bad.png"), 3, 2, nullptr), Error);
}

// An uncompressed TGA, written by hand so that stb's grey and alpha paths are exercised.
Bytes tga(int width, int height, int bytes_per_pixel, const Bytes& pixels) {
  Bytes bytes(18 + pixels.size(), 0);
  bytes[2] = bytes_per_pixel == 1 ? 3 : 2;  // grey or true colour, uncompressed
  bytes[12] = static_cast<unsigned char>(width);
  bytes[13] = static_cast<unsigned char>(width >> 8);
  bytes[14] = static_cast<unsigned char>(height);
  bytes[15] = static_cast<unsigned char>(height >> 8);
  bytes[16] = static_cast<unsigned char>(8 * bytes_per_pixel);
  bytes[17] = 0x20 | (bytes_per_pixel == 4 ? 8 : 0);  // top-left origin, alpha bits
  std::copy(pixels.begin(), pixels.end(), bytes.begin() + 18);
  return bytes;
}

TEST_F(ImageIoTest, LoadsGreyAndRgbaAsLinearRgb) {
  // Grey, 3 x 2: each value is replicated to R, G and B.
  write_bytes(path("grey.tga"), tga(3, 2, 1, {0, 64, 128, 192, 255, 32}));
  const Image grey = load_image(path("grey.tga"));
  ASSERT_EQ(grey.width(), 3);
  ASSERT_EQ(grey.height(), 2);
  EXPECT_EQ(grey.at(2, 0), vec3(srgb_decode(128 / 255.0f)));
  EXPECT_EQ(grey.at(0, 1), vec3(srgb_decode(192 / 255.0f)));
  EXPECT_EQ(grey.at(2, 1), vec3(srgb_decode(32 / 255.0f)));

  // BGRA, 2 x 1: alpha is dropped and does not premultiply the colour.
  write_bytes(path("rgba.TGA"), tga(2, 1, 4, {255, 0, 0, 0, 10, 20, 30, 128}));
  const Image rgba = load_image(path("rgba.TGA"));
  ASSERT_EQ(rgba.width(), 2);
  EXPECT_EQ(rgba.at(0, 0), vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(rgba.at(1, 0),
            vec3(srgb_decode(30 / 255.0f), srgb_decode(20 / 255.0f), srgb_decode(10 / 255.0f)));
}

TEST_F(ImageIoTest, Loads16BitPngAtFullPrecision) {
  // A 2 x 1 16-bit RGB PNG with pixels (65535, 0, 32768) and (1000, 50000, 65535).
  const Bytes png = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49,
                     0x48, 0x44, 0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x10, 0x02,
                     0x00, 0x00, 0x00, 0x2b, 0xd0, 0x34, 0x9e, 0x00, 0x00, 0x00, 0x15, 0x49, 0x44,
                     0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xff, 0x9f, 0x81, 0xa1, 0x81, 0x81, 0xf9,
                     0xc5, 0xe1, 0x80, 0xff, 0xff, 0x01, 0x26, 0x89, 0x06, 0x7b, 0xf5, 0x13, 0x05,
                     0xb7, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  write_bytes(path("deep.png"), png);
  const Image image = load_image(path("deep.png"));
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.height(), 1);
  EXPECT_EQ(image.at(0, 0), vec3(1.0f, 0.0f, srgb_decode(32768 / 65535.0f)));
  EXPECT_EQ(image.at(1, 0),
            vec3(srgb_decode(1000 / 65535.0f), srgb_decode(50000 / 65535.0f), 1.0f));
}

TEST_F(ImageIoTest, ExrExactRoundTrip) {
  const Image image = hdr_test_image(5, 3);
  save_image(path("hdr.exr"), image, 3.0f);  // exposure does not apply to linear formats
  const Image loaded = load_image(path("hdr.exr"));
  expect_images_identical(loaded, image);
  EXPECT_EQ(loaded.at(4, 0), vec3(17.0f, 0.0f, 0.5f));
}

TEST_F(ImageIoTest, PfmExactRoundTrip) {
  const Image image = hdr_test_image(3, 5);
  save_image(path("hdr.pfm"), image, -2.0f);
  const Image loaded = load_image(path("hdr.pfm"));
  expect_images_identical(loaded, image);
  EXPECT_EQ(loaded.at(2, 0), vec3(17.0f, 0.0f, 0.5f));
}

TEST_F(ImageIoTest, ExtensionsAreCaseInsensitive) {
  const Image image = hdr_test_image(2, 3);
  save_image(path("upper.EXR"), image);
  expect_images_identical(load_image(path("upper.EXR")), image);
  save_image(path("upper.Pfm"), image);
  expect_images_identical(load_image(path("upper.Pfm")), image);
  save_image(path("upper.PNG"), Image(2, 2, vec3(1.0f)));
  EXPECT_EQ(load_image(path("upper.PNG")).at(1, 1), vec3(1.0f));
}

TEST_F(ImageIoTest, PfmStoresRowsBottomToTop) {
  save_image(path("rows.pfm"), hdr_test_image(2, 2));
  const Bytes bytes = read_bytes(path("rows.pfm"));
  const std::string header = "PF\n2 2\n-1.0\n";
  ASSERT_EQ(std::string(bytes.begin(), bytes.begin() + header.size()), header);
  ASSERT_EQ(bytes.size(), header.size() + 2 * 2 * 12);
  // The marker at the top-right pixel (1, 0) is the last pixel in the file.
  float red = 0.0f;
  std::memcpy(&red, bytes.data() + header.size() + 3 * 12, 4);
  EXPECT_EQ(red, 17.0f);
}

TEST_F(ImageIoTest, LoadsBigEndianGreyPfm) {
  // 2 x 2 grey, big-endian (positive scale), rows bottom to top, single-space separators.
  Bytes bytes;
  append_text(bytes, "Pf 2 2 1.0\n");
  for (float v : {1.0f, 2.0f, 3.5f, 400.0f}) append_float(bytes, v, false);
  write_bytes(path("grey.pfm"), bytes);
  const Image image = load_image(path("grey.pfm"));
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.height(), 2);
  EXPECT_EQ(image.at(0, 1), vec3(1.0f));
  EXPECT_EQ(image.at(1, 1), vec3(2.0f));
  EXPECT_EQ(image.at(0, 0), vec3(3.5f));
  EXPECT_EQ(image.at(1, 0), vec3(400.0f));
}

TEST_F(ImageIoTest, LoadsLittleEndianColourPfm) {
  Bytes bytes;
  append_text(bytes, "PF\n1 2\n-4.0\n");
  for (float v : {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f}) append_float(bytes, v, true);
  write_bytes(path("colour.pfm"), bytes);
  const Image image = load_image(path("colour.pfm"));
  EXPECT_EQ(image.at(0, 1), vec3(1.0f, 2.0f, 3.0f));  // first stored row is the bottom one
  EXPECT_EQ(image.at(0, 0), vec3(4.0f, 5.0f, 6.0f));
}

TEST_F(ImageIoTest, MissingFileThrowsWithPath) {
  for (const char* name : {"missing.png", "missing.exr", "missing.pfm", "missing.jpg"}) {
    expect_error_containing([&] { load_image(path(name)); }, {path(name), "not found"});
  }
}

TEST_F(ImageIoTest, UnknownExtensionThrows) {
  write_bytes(path("image.xyz"), {1, 2, 3});
  expect_error_containing([&] { load_image(path("image.xyz")); }, {path("image.xyz"), ".xyz"});
  expect_error_containing([&] { save_image(path("out.gif"), Image(1, 1)); }, {path("out.gif")});
  expect_error_containing([&] { save_image(path("noext"), Image(1, 1)); }, {path("noext")});
  EXPECT_TRUE(directory_entries().size() == 1);
}

TEST_F(ImageIoTest, EmptyFileAndEmptyImageThrow) {
  write_bytes(path("empty.png"), {});
  expect_error_containing([&] { load_image(path("empty.png")); }, {path("empty.png"), "empty"});
  expect_error_containing([&] { save_image(path("out.exr"), Image()); }, {path("out.exr")});
}

TEST_F(ImageIoTest, TruncatedPngThrowsWithPath) {
  save_image(path("full.png"), ldr_test_image(16, 16));
  Bytes bytes = read_bytes(path("full.png"));
  bytes.resize(bytes.size() / 2);
  write_bytes(path("cut.png"), bytes);
  expect_error_containing([&] { load_image(path("cut.png")); }, {path("cut.png")});
  write_bytes(path("text.png"), Bytes{'h', 'e', 'l', 'l', 'o'});
  expect_error_containing([&] { load_image(path("text.png")); }, {path("text.png")});
}

TEST_F(ImageIoTest, TruncatedExrThrowsWithPath) {
  save_image(path("full.exr"), hdr_test_image(64, 48));
  const Bytes full = read_bytes(path("full.exr"));
  for (size_t size : {size_t(3), size_t(40), full.size() / 2, full.size() - 1}) {
    write_bytes(path("cut.exr"), Bytes(full.begin(), full.begin() + size));
    expect_error_containing([&] { load_image(path("cut.exr")); }, {path("cut.exr")});
  }
  write_bytes(path("garbage.exr"), Bytes(100, 0x5a));
  expect_error_containing([&] { load_image(path("garbage.exr")); }, {path("garbage.exr")});
}

TEST_F(ImageIoTest, BadPfmThrowsWithPath) {
  const std::vector<std::string> headers = {
      "P6\n2 2\n255\n",                           // a PPM, not a PFM
      "PF\nabc 2\n-1.0\n",                        // width is not a number
      "PF\n2 -2\n-1.0\n",                         // negative height
      "PF\n0 2\n-1.0\n",                          // zero width
      "PF\n2 2\n0.0\n",                           // zero scale
      "PF\n2 2\nnan\n",                           // no endianness
      "PF\n2 2\n-1.0",                            // nothing after the scale
      "PF\n99999999 99999999\n-1.0\n",            // absurd size
      "PF\n2 2\n-1.0\n" + std::string(47, '\0'),  // one byte short of 2 x 2 x 12
  };
  for (const std::string& text : headers) {
    Bytes bytes;
    append_text(bytes, text);
    write_bytes(path("bad.pfm"), bytes);
    expect_error_containing([&] { load_image(path("bad.pfm")); }, {path("bad.pfm")});
  }
}

TEST_F(ImageIoTest, SaveIntoMissingDirectoryThrowsAndCreatesNothing) {
  const std::string target = path("no/such/dir/out.png");
  for (const char* name : {"out.png", "out.exr", "out.pfm"}) {
    const std::string file = path(std::string("missing/") + name);
    expect_error_containing([&] { save_image(file, Image(2, 2)); }, {file, "does not exist"});
  }
  expect_error_containing([&] { save_png_rgb8(target, 1, 1, std::vector<uint8_t>(3).data()); },
                          {target});
  EXPECT_TRUE(directory_entries().empty());
}

TEST_F(ImageIoTest, SaveLeavesNoTemporaryFile) {
  save_image(path("a.png"), Image(2, 2, vec3(0.5f)));
  save_image(path("b.exr"), Image(2, 2, vec3(0.5f)));
  save_image(path("c.pfm"), Image(2, 2, vec3(0.5f)));
  const std::vector<uint8_t> rgb(12, 7);
  save_png_rgb8(path("d.png"), 2, 2, rgb.data());
  std::vector<std::string> names = directory_entries();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"a.png", "b.exr", "c.pfm", "d.png"}));
}

TEST_F(ImageIoTest, SaveReplacesAnExistingFile) {
  save_image(path("x.pfm"), Image(4, 4, vec3(1.0f)));
  save_image(path("x.pfm"), Image(1, 2, vec3(2.0f)));
  const Image loaded = load_image(path("x.pfm"));
  EXPECT_EQ(loaded.width(), 1);
  EXPECT_EQ(loaded.at(0, 1), vec3(2.0f));
  EXPECT_EQ(directory_entries().size(), 1u);
}

TEST_F(ImageIoTest, SaveOntoADirectoryThrows) {
  fs::create_directory(path("taken.png"));
  expect_error_containing([&] { save_image(path("taken.png"), Image(1, 1)); }, {path("taken.png")});
  EXPECT_EQ(directory_entries().size(), 1u);
}

}  // namespace
}  // namespace bounce
