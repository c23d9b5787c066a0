// What every fuzz target does with its input once a loader has accepted it: the path a user's file
// takes (load, post-load validation in Scene::finalize, one tiny frame), in process, so a crash or
// sanitizer report anywhere along it is found. Errors (bounce::Error) are the expected outcome of
// most inputs and are swallowed; anything else escapes and libFuzzer reports it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "bounce/scene/scene.h"

namespace bounce::fuzz {

// Writes the input to this process's scratch file ending in `extension` (loaders that read paths
// need one) and returns its path. Under /dev/shm when it exists, so each run stays in memory.
std::string scratch_file(const uint8_t* data, size_t size, const std::string& extension);

// Renders, on one thread, one 8x8 frame of the scene's camera with the default technique (tiled,
// few photons) and one with direct light: tracer build, photon tracing and gathering, denoiser.
void render_tiny(const Scene& scene);

// Loads `path` with load_scene (which validates) and renders it tiny; bounce::Error is the input
// being refused, which is fine.
void load_and_render(const std::string& path);

}  // namespace bounce::fuzz
