#include "bounce/core/image_io.h"
#include "bounce/core/tonemap.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include <IexBaseExc.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
// libstb ships the compiled implementation, so only the declarations are included here.
#include <stb_image.h>
#include <stb_image_write.h>

#include "bounce/core/color.h"
#include "bounce/core/error.h"
#include "bounce/core/input_file.h"
#include "bounce/core/interrupt.h"
#include "bounce/core/rgbe.h"

namespace bounce {

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;

// A corrupt header must not make us allocate absurd amounts of memory (2^28 pixels = 3 GiB).
constexpr int64_t kMaxPixels = int64_t(1) << 28;
constexpr std::array<const char*, 3> kRgbChannels = {"R", "G", "B"};

static_assert(sizeof(vec3) == 3 * sizeof(float), "Image pixels must be three packed floats");

// ---------------------------------------------------------------------------------------------
// Helpers shared by the formats

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); });
  return ext;
}

std::string describe_extension(const std::string& ext) {
  return ext.empty() ? std::string("no file extension")
                     : fmt::format("unsupported file extension '{}'", ext);
}

std::string errno_message(int error) {
  return std::error_code(error, std::generic_category()).message();
}

void check_size(const std::string& path, int64_t width, int64_t height) {
  if (width <= 0 || height <= 0) {
    fail("cannot read {}: invalid image size {}x{}", path, width, height);
  }
  if (width > kMaxPixels || height > kMaxPixels || width * height > kMaxPixels) {
    fail("cannot read {}: image size {}x{} is too large", path, width, height);
  }
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

Bytes read_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("cannot read {}: file not found", path);
  if (fs::is_directory(path, ec)) fail("cannot read {}: it is a directory", path);
  check_regular_file(path, "image");
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) fail("cannot read {}: {}", path, errno_message(errno));
  Bytes bytes;
  std::array<unsigned char, 1 << 16> chunk;
  size_t count = 0;
  while ((count = std::fread(chunk.data(), 1, chunk.size(), file.get())) > 0) {
    bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + count);
  }
  if (std::ferror(file.get())) fail("cannot read {}: read error", path);
  if (bytes.empty()) fail("cannot read {}: the file is empty", path);
  return bytes;
}

// Writes bytes to a file; returns an empty string on success, else what went wrong.
std::string write_bytes(const std::string& file_name, const Bytes& bytes) {
  std::FILE* file = std::fopen(file_name.c_str(), "wb");
  if (!file) return errno_message(errno);
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  const int write_error = errno;
  // fclose flushes, so it reports a full disk that fwrite's buffering hid.
  const bool closed = std::fclose(file) == 0;
  if (!written) return errno_message(write_error);
  if (!closed) return errno_message(errno);
  return {};
}

// A temporary name in the target's directory (rename is only atomic within one file system);
// the pid and a counter keep concurrent saves of the same path apart.
std::string temporary_path(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return fmt::format("{}.tmp-{}-{}", path, ::getpid(), counter++);
}

// Writes a temporary file and renames it over the target, so the target is either the old file
// or the complete new one, never a partial write.
void write_file_atomically(const std::string& path, const Bytes& bytes,
                           bool finish_when_interrupted = false) {
  const fs::path target(path);
  const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    if (fs::exists(directory, ec)) {
      fail("cannot write {}: '{}' is not a directory", path, directory.string());
    }
    fail("cannot write {}: directory '{}' does not exist", path, directory.string());
  }
  if (fs::is_directory(target, ec)) fail("cannot write {}: it is a directory", path);
  const std::string temporary = temporary_path(path);
  const std::string problem = write_bytes(temporary, bytes);
  if (!problem.empty()) {
    fs::remove(temporary, ec);
    fail("cannot write {}: {}", path, problem);
  }
  // A signal during the write: leave the target as it was and no temporary file behind (unless
  // the write is what the interrupt is for, as a checkpoint is).
  if (interrupt_signal() != 0 && !finish_when_interrupted) {
    fs::remove(temporary, ec);
    throw_if_interrupted();
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    fail("cannot write {}: {}", path, ec.message());
  }
}

// Runs an encoder, turning any third-party exception into an Error that names the path.
template <typename Encode>
Bytes encode_or_fail(const std::string& path, Encode encode) {
  try {
    return encode();
  } catch (const std::exception& e) {
    fail("cannot write {}: {}", path, e.what());
  }
}

// ---------------------------------------------------------------------------------------------
// 8-bit formats through stb

struct StbFree {
  void operator()(void* pixels) const { stbi_image_free(pixels); }
};

const std::array<float, 256>& srgb8_to_linear_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values;
    for (int i = 0; i < 256; ++i) values[i] = srgb_decode(float(i) / 255.0f);
    return values;
  }();
  return table;
}

[[noreturn]] void fail_stb(const std::string& path) {
  // stb's reasons are terse ("outofdata") and sometimes empty, so they only add detail.
  const char* reason = stbi_failure_reason();
  fail("cannot read {}: corrupt, truncated or unsupported image{}", path,
       reason && *reason ? fmt::format(" (stb_image: {})", reason) : std::string());
}

// Decodes 16-bit PNGs at full precision; asking stb for 3 channels expands grey, drops alpha.
Image decode_ldr16(const std::string& path, const Bytes& bytes) {
  int width = 0, height = 0, channels_in_file = 0;
  std::unique_ptr<stbi_us, StbFree> pixels(stbi_load_16_from_memory(
      bytes.data(), int(bytes.size()), &width, &height, &channels_in_file, 3));
  if (!pixels) fail_stb(path);
  check_size(path, width, height);
  Image image(width, height);
  const stbi_us* p = pixels.get();
  for (vec3& pixel : image.pixels()) {
    for (int c = 0; c < 3; ++c) pixel[c] = srgb_decode(float(*p++) / 65535.0f);
  }
  return image;
}

Image decode_ldr(const std::string& path, const Bytes& bytes) {
  if (bytes.size() > size_t(INT_MAX)) fail("cannot read {}: the file is too large", path);
  if (stbi_is_16_bit_from_memory(bytes.data(), int(bytes.size()))) {
    return decode_ldr16(path, bytes);
  }
  int width = 0, height = 0, channels_in_file = 0;
  std::unique_ptr<stbi_uc, StbFree> pixels(stbi_load_from_memory(
      bytes.data(), int(bytes.size()), &width, &height, &channels_in_file, 3));
  if (!pixels) fail_stb(path);
  check_size(path, width, height);
  const std::array<float, 256>& to_linear = srgb8_to_linear_table();
  Image image(width, height);
  const stbi_uc* p = pixels.get();
  for (vec3& pixel : image.pixels()) {
    for (int c = 0; c < 3; ++c) pixel[c] = to_linear[*p++];
  }
  return image;
}

struct PngSink {
  Bytes bytes;
  bool failed = false;
};

Bytes encode_png(int width, int height, const uint8_t* rgb) {
  PngSink sink;
  // No exception may cross stb's C frames, so the callback records a failure instead.
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<PngSink*>(context);
    try {
      const auto* begin = static_cast<const unsigned char*>(data);
      out->bytes.insert(out->bytes.end(), begin, begin + size);
    } catch (...) {
      out->failed = true;
    }
  };
  const int ok = stbi_write_png_to_func(append, &sink, width, height, 3, rgb, width * 3);
  if (!ok || sink.failed) throw std::runtime_error("PNG encoding failed");
  return std::move(sink.bytes);
}

// ---------------------------------------------------------------------------------------------
// OpenEXR, through in-memory streams so that file access and atomic writes stay in one place

class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const std::string& name, const Bytes& bytes)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}

  bool read(char c[], int n) override {
    if (n < 0 || position_ > bytes_.size() || uint64_t(n) > bytes_.size() - position_) {
      throw Iex::InputExc("unexpected end of file (truncated EXR)");
    }
    std::memcpy(c, bytes_.data() + position_, size_t(n));
    position_ += uint64_t(n);
    return position_ < bytes_.size();
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t position) override { position_ = position; }

 private:
  const Bytes& bytes_;
  uint64_t position_ = 0;
};

class MemoryOStream : public Imf::OStream {
 public:
  explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}

  void write(const char c[], int n) override {
    const uint64_t end = position_ + uint64_t(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, size_t(n));
    position_ = end;
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = position; }
  Bytes take() { return std::move(bytes_); }

 private:
  Bytes bytes_;
  uint64_t position_ = 0;
};

// Points the R, G and B float slices at an image covering the given data window.
Imf::FrameBuffer rgb_frame_buffer(const Image& image, const Imath::Box2i& window) {
  const char* base = reinterpret_cast<const char*>(image.data());
  const size_t x_stride = sizeof(vec3);
  const size_t y_stride = sizeof(vec3) * size_t(image.width());
  Imf::FrameBuffer frame_buffer;
  for (size_t c = 0; c < kRgbChannels.size(); ++c) {
    frame_buffer.insert(kRgbChannels[c], Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float),
                                                          window, x_stride, y_stride));
  }
  return frame_buffer;
}

Image read_exr_pixels(const std::string& path, Imf::InputFile& file) {
  const Imf::Header& header = file.header();
  const Imath::Box2i window = header.dataWindow();
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  check_size(path, width, height);
  for (const char* name : kRgbChannels) {
    if (!header.channels().findChannel(name)) {
      fail("cannot read {}: the EXR has no '{}' channel (R, G and B are required)", path, name);
    }
  }
  Image image(static_cast<int>(width), static_cast<int>(height));
  file.setFrameBuffer(rgb_frame_buffer(image, window));
  file.readPixels(window.min.y, window.max.y);
  return image;
}

Image decode_exr(const std::string& path, const Bytes& bytes) {
  try {
    MemoryIStream stream(path, bytes);
    Imf::InputFile file(stream);
    return read_exr_pixels(path, file);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("cannot read {}: {}", path, e.what());
  }
}

Bytes encode_exr(const std::string& path, const Image& image,
                 const ImageAttributes& attributes = {}) {
  Imf::Header header(image.width(), image.height());
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const auto& [name, value] : attributes) header.insert(name, Imf::StringAttribute(value));
  for (const char* name : kRgbChannels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  MemoryOStream stream(path);
  {
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(rgb_frame_buffer(image, header.dataWindow()));
    file.writePixels(image.height());
  }  // The destructor writes the line offset table, so the bytes are complete only after it.
  return stream.take();
}

// ---------------------------------------------------------------------------------------------
// PFM: "PF" (RGB) or "Pf" (grey), width, height, scale (negative = little-endian), then float
// rows from the bottom of the image to the top.

struct PfmHeader {
  int width = 0;
  int height = 0;
  int channels = 0;
  bool little_endian = true;
  size_t data_offset = 0;
};

bool is_space(unsigned char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

std::string_view next_token(const Bytes& bytes, size_t& pos) {
  while (pos < bytes.size() && is_space(bytes[pos])) ++pos;
  const size_t start = pos;
  // A header token is short; stop early so that binary garbage is not scanned to the end.
  while (pos < bytes.size() && !is_space(bytes[pos]) && pos - start < 32) ++pos;
  return {reinterpret_cast<const char*>(bytes.data()) + start, pos - start};
}

std::string printable(std::string_view token) {
  std::string result(token);
  for (char& c : result) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  return result;
}

template <typename T>
T parse_pfm_number(const std::string& path, std::string_view token, const char* what) {
  T value{};
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) {
    fail("cannot read {}: invalid PFM header: bad {} '{}'", path, what, printable(token));
  }
  return value;
}

PfmHeader parse_pfm_header(const std::string& path, const Bytes& bytes) {
  if (bytes.size() < 3 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f') ||
      !is_space(bytes[2])) {
    fail("cannot read {}: not a PFM file (it must start with \"PF\" or \"Pf\")", path);
  }
  PfmHeader header;
  header.channels = bytes[1] == 'F' ? 3 : 1;
  size_t pos = 2;
  header.width = parse_pfm_number<int>(path, next_token(bytes, pos), "width");
  header.height = parse_pfm_number<int>(path, next_token(bytes, pos), "height");
  const float scale = parse_pfm_number<float>(path, next_token(bytes, pos), "scale");
  if (scale == 0.0f || !std::isfinite(scale)) {
    fail("cannot read {}: invalid PFM header: scale must be finite and non-zero", path);
  }
  header.little_endian = scale < 0.0f;
  // Exactly one whitespace byte separates the header from the pixels.
  if (pos >= bytes.size() || !is_space(bytes[pos])) {
    fail("cannot read {}: invalid PFM header: no pixel data after the scale", path);
  }
  header.data_offset = pos + 1;
  check_size(path, header.width, header.height);
  const size_t needed = size_t(header.width) * size_t(header.height) * header.channels * 4;
  const size_t available = bytes.size() - header.data_offset;
  if (available < needed) {
    fail("cannot read {}: truncated PFM: {} bytes of pixel data, expected {}", path, available,
         needed);
  }
  return header;
}

float load_float(const unsigned char* p, bool little_endian) {
  uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) {
    const uint32_t byte = little_endian ? p[i] : p[3 - i];
    bits |= byte << (8 * i);
  }
  return std::bit_cast<float>(bits);
}

void append_float_le(Bytes& bytes, float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<unsigned char>(bits >> (8 * i)));
}

Image decode_pfm(const std::string& path, const Bytes& bytes) {
  const PfmHeader header = parse_pfm_header(path, bytes);
  Image image(header.width, header.height);
  const unsigned char* p = bytes.data() + header.data_offset;
  for (int row = 0; row < header.height; ++row) {
    const int y = header.height - 1 - row;
    for (int x = 0; x < header.width; ++x) {
      vec3 pixel;
      for (int c = 0; c < header.channels; ++c, p += 4)
        pixel[c] = load_float(p, header.little_endian);
      image.at(x, y) = header.channels == 3 ? pixel : vec3(pixel.x);
    }
  }
  return image;
}

Bytes encode_pfm(const Image& image) {
  const std::string header = fmt::format("PF\n{} {}\n-1.0\n", image.width(), image.height());
  Bytes bytes(header.begin(), header.end());
  bytes.reserve(header.size() + image.pixel_count() * 12);
  for (int y = image.height() - 1; y >= 0; --y) {
    for (int x = 0; x < image.width(); ++x) {
      const vec3 pixel = image.at(x, y);
      for (int c = 0; c < 3; ++c) append_float_le(bytes, pixel[c]);
    }
  }
  return bytes;
}

bool is_ldr_extension(const std::string& ext) {
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tga" || ext == ".bmp";
}

}  // namespace

Image load_image(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (!is_ldr_extension(ext) && ext != ".exr" && ext != ".pfm" && ext != ".hdr") {
    fail("cannot read {}: {} (expected .png, .jpg, .jpeg, .tga, .bmp, .exr, .hdr or .pfm)", path,
         describe_extension(ext));
  }
  const Bytes bytes = read_file(path);
  if (ext == ".exr") return decode_exr(path, bytes);
  if (ext == ".hdr") return decode_rgbe(path, bytes.data(), bytes.size());
  if (ext == ".pfm") return decode_pfm(path, bytes);
  return decode_ldr(path, bytes);
}

void save_image(const std::string& path, const Image& image, float exposure_ev) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".exr" && ext != ".pfm") {
    fail("cannot write {}: {} (expected .png, .exr or .pfm)", path, describe_extension(ext));
  }
  if (image.empty()) fail("cannot write {}: the image is empty", path);
  const Bytes bytes = encode_or_fail(path, [&] {
    if (ext == ".png") {
      std::vector<uint8_t> rgb;
      tonemap_srgb8(image, exposure_ev, rgb);
      return encode_png(image.width(), image.height(), rgb.data());
    }
    return ext == ".exr" ? encode_exr(path, image) : encode_pfm(image);
  });
  write_file_atomically(path, bytes);
}

void save_png_rgb8(const std::string& path, int width, int height, const uint8_t* rgb) {
  if (width <= 0 || height <= 0 || width > INT_MAX / 3) {
    fail("cannot write {}: invalid image size {}x{}", path, width, height);
  }
  if (!rgb) fail("cannot write {}: no pixel data", path);
  const Bytes bytes = encode_or_fail(path, [&] { return encode_png(width, height, rgb); });
  write_file_atomically(path, bytes);
}

void save_text_file(const std::string& path, const std::string& text,
                    bool finish_when_interrupted) {
  write_file_atomically(path, Bytes(text.begin(), text.end()), finish_when_interrupted);
}

void save_exr(const std::string& path, const Image& image, const ImageAttributes& attributes) {
  if (lower_extension(path) != ".exr") fail("cannot write {}: attributes need an .exr file", path);
  if (image.empty()) fail("cannot write {}: the image is empty", path);
  write_file_atomically(path,
                        encode_or_fail(path, [&] { return encode_exr(path, image, attributes); }));
}

Image load_exr(const std::string& path, ImageAttributes& attributes) {
  if (lower_extension(path) != ".exr")
    fail("cannot read {}: {} (expected .exr)", path, describe_extension(lower_extension(path)));
  const Bytes bytes = read_file(path);
  try {
    MemoryIStream stream(path, bytes);
    Imf::InputFile file(stream);
    attributes.clear();
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
      if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        attributes[it.name()] = text->value();
    return read_exr_pixels(path, file);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("cannot read {}: {}", path, e.what());
  }
}

}  // namespace bounce
