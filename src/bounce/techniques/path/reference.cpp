#include "bounce/techniques/path/reference.h"

#include <algorithm>
#include <atomic>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/timer.h"
#include "bounce/scene/scene_data.h"

namespace bounce {

namespace {

constexpr int kTile = 16;
constexpr double kPassSeconds = 0.5;

// Adds samples [first, first + count) of every pixel of one tile to the running sums.
void render_tile(const PathScene& ps, const PathSettings& path, const CameraRays& camera,
                 uint32_t seed, int x0, int y0, int x1, int y1, int first, int count, int width,
                 double* sums, PathCounters& counters) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
      double r = 0.0, g = 0.0, b = 0.0;
      for (int k = first; k < first + count; ++k) {
        Pcg32 rng = path_rng(pixel, uint32_t(k), seed);
        const vec2 jitter = rng.next2();  // box filter: uniform over the pixel's square
        const vec3 direction = camera.direction(float(x) + jitter.x, float(y) + jitter.y);
        const vec3 l = ray_radiance(ps, path, camera.origin, direction, rng, counters);
        r += l.x;
        g += l.y;
        b += l.z;
      }
      sums[3 * size_t(pixel) + 0] += r;
      sums[3 * size_t(pixel) + 1] += g;
      sums[3 * size_t(pixel) + 2] += b;
    }
}

}  // namespace

ReferenceResult render_reference(const Scene& scene, const Tracer& tracer, const Camera& camera,
                                 const ReferenceSettings& settings,
                                 const ReferenceProgressFn& progress, ReferenceState* state) {
  if (settings.width <= 0 || settings.height <= 0)
    fail("image size {}x{} is not positive", settings.width, settings.height);
  if (settings.spp <= 0) fail("samples per pixel must be positive (got {})", settings.spp);
  if (settings.time_limit_s < 0.0) fail("time limit {} s is negative", settings.time_limit_s);
  if (settings.first_sample < 0 || settings.first_sample > kMaxReferenceSample - settings.spp)
    fail("samples {} .. {} are outside the sample sequence (0 .. {})", settings.first_sample,
         int64_t(settings.first_sample) + settings.spp - 1, kMaxReferenceSample - 1);

  const LightPicker lights = LightPicker::build(scene);
  const SceneData data = SceneData::from(scene);
  const PathScene ps = path_scene(data.view(), tracer, lights);
  PathSettings path = settings.path;
  path.min_bounces = 0;
  const int w = settings.width, h = settings.height;
  const CameraRays camera_rays = CameraRays::from(camera, w, h);
  ReferenceState own;
  ReferenceState& st = state ? *state : own;
  if (st.sums.empty()) {
    st.width = w;
    st.height = h;
    st.spp = 0;
    st.sums.assign(size_t(w) * h * 3, 0.0);
  }
  if (st.width != w || st.height != h || st.sums.size() != size_t(w) * h * 3)
    fail("reference: the saved samples are {}x{}, the image is {}x{}", st.width, st.height, w, h);
  if (st.spp < 0 || st.spp >= settings.spp)
    fail("reference: {} samples per pixel are already taken; ask for more than that with --spp",
         st.spp);
  std::vector<double>& sums = st.sums;
  std::atomic<uint64_t> rays{0}, nonfinite{0};

  const Stopwatch watch;
  const double limit = settings.time_limit_s;
  const int resumed = st.spp;
  int done = st.spp, pass = 1;
  while (done < settings.spp) {
    const double elapsed = watch.elapsed_ms() * 1e-3;
    const int taken = done - resumed;  // samples of this run: what the time limit measures
    if (limit > 0.0 && taken > 0 && elapsed >= limit) break;
    int count = std::min(pass, settings.spp - done);
    if (limit > 0.0 && taken > 0)
      count = std::min(count, std::max(1, int((limit - elapsed) / (elapsed / taken))));
    parallel_for_tiles(w, h, kTile, [&](int x0, int y0, int x1, int y1) {
      PathCounters counters;
      render_tile(ps, path, camera_rays, settings.seed, x0, y0, x1, y1,
                  settings.first_sample + done, count, w, sums.data(), counters);
      rays += counters.rays;
      nonfinite += counters.nonfinite;
    });
    done += count;
    st.spp = done;
    const double seconds = watch.elapsed_ms() * 1e-3;
    const double per_spp = seconds / (done - resumed);
    pass = int(std::clamp(kPassSeconds / std::max(per_spp, 1e-9), 1.0, 65536.0));
    if (progress) {
      ReferenceProgress p;
      p.spp_done = done;
      p.spp_target = settings.spp;
      p.elapsed_s = seconds;
      p.fraction = double(done) / settings.spp;
      if (limit > 0.0) p.fraction = std::max(p.fraction, std::min(1.0, seconds / limit));
      const double run_fraction = double(done - resumed) / (settings.spp - resumed);
      p.eta_s = run_fraction > 0.0 ? seconds * (1.0 - run_fraction) / run_fraction : 0.0;
      if (limit > 0.0) p.eta_s = std::min(p.eta_s, std::max(0.0, limit - seconds));
      progress(p);
    }
  }

  ReferenceResult result;
  result.spp = done;
  result.seconds = watch.elapsed_ms() * 1e-3;
  result.rays = rays;
  result.nonfinite = nonfinite;
  result.image = Image(w, h);
  const double inv = 1.0 / done;
  for (size_t i = 0; i < result.image.pixel_count(); ++i)
    result.image.pixels()[i] =
        vec3(float(sums[3 * i] * inv), float(sums[3 * i + 1] * inv), float(sums[3 * i + 2] * inv));
  return result;
}

}  // namespace bounce
