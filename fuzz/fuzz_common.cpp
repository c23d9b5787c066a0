#include "fuzz_common.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"
#include "bounce/trace/tracer.h"

namespace bounce::fuzz {

std::string scratch_file(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  const std::string path = dir + "/bounce-fuzz-" + std::to_string(::getpid()) + extension;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();  // the harness itself is broken: stop at once
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

void render_tiny(const Scene& scene) {
  // One thread: a fuzz run takes one core (runs of several targets can share a machine), and an
  // 8x8 frame spends more on handing work to other threads than on the work.
  static const ThreadLimit one_thread(1);
  FrameSettings settings;
  settings.width = 8;
  settings.height = 8;
  settings.light_samples = 1;
  auto tracer = make_embree_tracer(scene);
  for (const char* name : {"direct", "tiled"}) {
    auto technique = make_technique(name);
    // A tiny frame needs few photons; the default would spend the run tracing them.
    if (technique->params().find("photons")) technique->params().set("photons", "64");
    Renderer renderer(scene, *tracer, std::move(technique));
    renderer.render(scene.camera, settings);
  }
}

void load_and_render(const std::string& path) {
  try {
    const Scene scene = load_scene(path);
    render_tiny(scene);
  } catch (const Error&) {
  }
}

}  // namespace bounce::fuzz
