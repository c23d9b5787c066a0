#include "bounce/render/gbuffer_direct.h"

#include <atomic>
#include <chrono>

#include "bounce/core/parallel.h"
#include "bounce/core/timer.h"

namespace bounce {

namespace {

// A band is this many whole rows of the frame: at 1280 pixels a row its G-buffer is about
// 530 KB (1.6 MB at 3840), within a core's 2 MB L2 until the direct light has read it, and the
// G-buffer's twelve arrays are written in whole rows (in blocks of 128 x 32 pixels, 1.5 KB
// pieces, its writes cost 1-2 ms more at 1280 x 720; docs/benchmarks.md).
constexpr int kBandRows = 4;

int64_t nanoseconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t)
      .count();
}

}  // namespace

GBufferAndDirect build_gbuffer_and_direct(const SceneView& scene, const LightPickerView& lights,
                                          const Tracer& tracer, const CameraRays& camera,
                                          vec2 subpixel, const DirectSettings& settings, GBuffer& g,
                                          Image& direct, Image* apart, const AfterBand& after_band,
                                          const PrimaryRaster* raster) {
  Stopwatch wall;
  DirectPass pass(scene, lights, tracer, g, camera.origin, settings, direct, apart);
  const GBufferView view = g.view();
  std::atomic<int64_t> gbuffer_ns{0}, direct_ns{0}, band_ns{0};
  parallel_for_tiles(g.width, g.height, g.width, kBandRows, [&](int x0, int y0, int x1, int y1) {
    const auto start = std::chrono::steady_clock::now();
    build_gbuffer_block(scene, tracer, camera, subpixel, view, x0, y0, x1, y1, raster);
    const int64_t surfaces = nanoseconds_since(start);
    pass.run(x0, y0, x1, y1);
    const int64_t both = nanoseconds_since(start);
    if (after_band) after_band(x0, y0, x1, y1);
    const int64_t all = after_band ? nanoseconds_since(start) : both;
    gbuffer_ns += surfaces;
    direct_ns += both - surfaces;
    band_ns += all - both;
  });
  GBufferAndDirect out;
  out.primary_rays = uint64_t(g.width) * uint64_t(g.height);
  out.shadow_rays = pass.shadow_rays();
  // The wall time shared in proportion to the threads' time in each part.
  const double ms = wall.elapsed_ms();
  const double parts[3] = {double(gbuffer_ns.load()), double(direct_ns.load()),
                           double(band_ns.load())};
  const double busy = parts[0] + parts[1] + parts[2];
  out.gbuffer_ms = busy > 0.0 ? ms * parts[0] / busy : 0.5 * ms;
  out.band_ms = busy > 0.0 ? ms * parts[2] / busy : 0.0;
  out.direct_ms = ms - out.gbuffer_ms - out.band_ms;
  return out;
}

}  // namespace bounce
