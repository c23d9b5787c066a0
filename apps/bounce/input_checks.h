// Checks on what the user typed, made before any scene is loaded or pixel rendered, so that a bad
// argument fails at once with a clear message instead of after minutes of work (or not at all).
#pragma once

#include <CLI/CLI.hpp>

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>

#include "bounce/scene/scene.h"

namespace bounce::app {

// Adds to every option of `app` and its subcommands a check that refuses a value that reads as a
// non-finite number ("nan", "inf", "-infinity", "1e999"): a range check lets NaN through, and no
// option of bounce means anything by such a value.
void refuse_non_finite_numbers(CLI::App& app);

// Exposure in stops, either way: 2^64 scales any radiance a scene may hold (scene_limits.h) to a
// value float still carries; more would only turn every pixel black or white.
inline constexpr float kMaxExposureEv = 64.0f;

// A check for -o/--out options: the empty string is refused (it would silently mean the default).
CLI::Validator non_empty_path();

// Checks an output image path before rendering: its extension is one save_image writes (.png,
// .exr, .pfm), its directory exists or can be created, and a file can be created there (throws
// Error naming the path and the problem).
void check_output_image(const std::string& path);

// The file name's extension in lower case, with its dot (".exr"); empty when it has none.
inline std::string lower_case_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Bytes per pixel of the frame pipeline (render, bench, sequence): output and accumulation
// images, G-buffer, the denoiser's history and filter buffers, the techniques' per-pixel buffers.
// Measured: peak resident memory grows by 470 bytes per pixel from 256x256 to 1024x1024 with
// tiled (path 450, direct 430), `/usr/bin/time -f %M bounce render -W N -H N --spp 1`.
inline constexpr uint64_t kFrameBytesPerPixel = 480;
// Bytes per pixel of `reference`: its sums in double precision and the output image.
inline constexpr uint64_t kReferenceBytesPerPixel = 48;

// The memory a render of `scene` at width x height is expected to need, in bytes: the pixels,
// geometry and the acceleration structure per triangle, textures, and what the technique keeps
// beyond its per-pixel buffers (Technique::memory_estimate: photons, refined meshes).
struct MemoryEstimate {
  uint64_t pixels = 0, geometry = 0, textures = 0, technique = 0;
  uint64_t total() const;
};
MemoryEstimate estimate_render_bytes(const Scene& scene, int width, int height,
                                     uint64_t bytes_per_pixel, uint64_t technique_bytes = 0);
// The cap on that estimate: BOUNCE_MEMORY_LIMIT_GB if set (a positive number of GiB), else
// kDefaultMemoryLimitGiB (throws Error for a malformed value).
uint64_t memory_limit_bytes();
inline constexpr double kDefaultMemoryLimitGiB = 8.0;
// Throws Error naming the estimate, its parts and the cap when the estimate exceeds the cap.
void check_memory(const Scene& scene, int width, int height,
                  uint64_t bytes_per_pixel = kFrameBytesPerPixel, uint64_t technique_bytes = 0);

}  // namespace bounce::app
