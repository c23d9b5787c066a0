#include "input_checks.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

#include "bounce/core/error.h"

namespace bounce::app {

namespace {

namespace fs = std::filesystem;

// Whether the whole text reads as a floating-point number that is NaN or infinite.
bool is_non_finite_number(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !std::isfinite(v);
}

void add_finite_check(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& value) {
        return is_non_finite_number(value) ? "'" + value + "' is not a finite number"
                                           : std::string();
      },
      "", "finite");  // no description: it would show on every option in --help
  for (CLI::Option* option : app.get_options())
    if (option->get_expected_max() > 0) option->check(finite);  // not flags
  for (CLI::App* sub : app.get_subcommands({})) add_finite_check(*sub);
}

// Per triangle: vertices, normals and texture coordinates, indices and material ids, and
// Embree's BVH (about twice the triangle data for its default build).
constexpr uint64_t kBytesPerTriangle = 200;

}  // namespace

void refuse_non_finite_numbers(CLI::App& app) {
  add_finite_check(app);
}

CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& value) {
        return value.empty() ? std::string("the file name is empty") : std::string();
      },
      "PATH", "non-empty");
}

void check_output_image(const std::string& path) {
  if (path.empty()) fail("the output file name is empty");
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".png" && ext != ".exr" && ext != ".pfm")
    fail("cannot write {}: {} (the output must end in .png, .exr or .pfm)", path,
         ext.empty() ? std::string("no file extension")
                     : fmt::format("unsupported file extension '{}'", ext));
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec)
      fail("cannot write {}: cannot create the directory '{}': {}", path, parent.string(),
           ec.message());
  }
  if (fs::is_directory(path, ec)) fail("cannot write {}: it is a directory", path);
  // Create (and remove) a file beside the target, as the image writer will: this finds a
  // read-only directory or a file system that takes no new files (such as /proc) now.
  const std::string probe = fmt::format("{}.probe-{}", path, ::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) fail("cannot write {}: {}", path, std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

uint64_t MemoryEstimate::total() const {
  const uint64_t parts[] = {pixels, geometry, textures, technique};
  uint64_t sum = 0;
  for (uint64_t part : parts)  // saturating: a technique's estimate may be UINT64_MAX
    sum = part > std::numeric_limits<uint64_t>::max() - sum ? std::numeric_limits<uint64_t>::max()
                                                            : sum + part;
  return sum;
}

MemoryEstimate estimate_render_bytes(const Scene& scene, int width, int height,
                                     uint64_t bytes_per_pixel, uint64_t technique_bytes) {
  MemoryEstimate e;
  e.pixels = uint64_t(width) * uint64_t(height) * bytes_per_pixel;
  e.geometry = uint64_t(scene.triangle_count()) * kBytesPerTriangle;
  for (const Texture& t : scene.textures) e.textures += t.texels.size() * sizeof(t.texels[0]);
  e.technique = technique_bytes;
  return e;
}

uint64_t memory_limit_bytes() {
  double gib = kDefaultMemoryLimitGiB;
  if (const char* text = std::getenv("BOUNCE_MEMORY_LIMIT_GB"); text != nullptr) {
    char* end = nullptr;
    gib = std::strtod(text, &end);
    if (*text == '\0' || *end != '\0' || !std::isfinite(gib) || gib <= 0.0 || gib > 1e9)
      fail("BOUNCE_MEMORY_LIMIT_GB='{}' is not a positive number of GiB", text);
  }
  return uint64_t(gib * 1024.0 * 1024.0 * 1024.0);
}

void check_memory(const Scene& scene, int width, int height, uint64_t bytes_per_pixel,
                  uint64_t technique_bytes) {
  const MemoryEstimate e =
      estimate_render_bytes(scene, width, height, bytes_per_pixel, technique_bytes);
  const uint64_t cap = memory_limit_bytes();
  const double gib = 1024.0 * 1024.0 * 1024.0;
  if (e.total() > cap)
    fail(
        "rendering {} at {}x{} needs about {:.1f} GiB (image {:.1f}, geometry {:.1f}, textures "
        "{:.1f}, photons and technique data {:.1f}), more than the cap of {:.1f} GiB; use a "
        "smaller image or fewer photons, or raise the cap with BOUNCE_MEMORY_LIMIT_GB=N",
        scene.source, width, height, double(e.total()) / gib, double(e.pixels) / gib,
        double(e.geometry) / gib, double(e.textures) / gib, double(e.technique) / gib,
        double(cap) / gib);
}

}  // namespace bounce::app
