// The denoiser stage on hand-built G-buffers: the a-trous filter's edges and means, albedo
// demodulation, running averages at rest, reprojection under a camera move and disocclusion,
// variance clipping when the world changed, the switches, parameters and debug views.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "bounce/core/error.h"
#include "bounce/core/parallel.h"
#include "bounce/core/rng.h"
#include "bounce/render/denoise_half.h"
#include "bounce/render/denoise_plan.h"
#include "bounce/render/denoiser.h"

namespace bounce {
namespace {

// A fronto-parallel plane at `depth` seen by every pixel: one object, albedo 1, no emission.
GBuffer plane(int w, int h, float depth = 1.0f) {
  GBuffer g;
  g.resize(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = g.view().index(x, y);
      g.position[i] = vec3(float(x), float(y), depth);
      g.normal[i] = g.geometric_normal[i] = vec3(0.0f, 0.0f, -1.0f);
      g.albedo[i] = vec3(1.0f);
      g.roughness[i] = 1.0f;
      g.f0[i] = vec3(0.0f);
      g.emission[i] = vec3(0.0f);
      g.depth[i] = depth;
      g.primitive[i] = 0;
      g.mesh[i] = 0;
      g.barycentric[i] = vec2(0.0f);
    }
  }
  return g;
}

Image image_of(int w, int h, const std::function<vec3(int, int)>& f) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) image.at(x, y) = f(x, y);
  return image;
}

// Grey light `level` times (1 + amplitude * u), u uniform in [-1, 1).
Image noisy(int w, int h, Pcg32& rng, float amplitude,
            const std::function<float(int, int)>& level) {
  return image_of(w, h, [&](int x, int y) {
    return vec3(level(x, y) * (1.0f + amplitude * (2.0f * rng.next_float() - 1.0f)));
  });
}

// Runs the denoiser on copies of the images and returns them.
struct Output {
  Image direct, indirect;
};
Output run(Denoiser& d, const GBuffer& g, HistoryState state, const Image& direct,
           const Image* indirect = nullptr, IndirectHistory history = IndirectHistory::kPerFrame) {
  StageTimes times;
  Output out{direct, indirect ? *indirect : Image()};
  d.run({g, state, history, times}, out.direct, indirect ? &out.indirect : nullptr);
  return out;
}

float mean_x(const Image& image, int x0, int x1, int y0, int y1) {
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += image.at(x, y).x;
  return float(sum / double((x1 - x0) * (y1 - y0)));
}

float deviation_x(const Image& image, int x0, int x1, int y0, int y1) {
  const float m = mean_x(image, x0, x1, y0, y1);
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += double(image.at(x, y).x - m) * (image.at(x, y).x - m);
  return float(std::sqrt(sum / double((x1 - x0) * (y1 - y0))));
}

// Where the modulation's history reaches the output: last frame's albedo factor and emission are
// reprojected in half precision (denoise::PackedPlanes), within 2^-11 of a value, and the blend
// keeps half of that in motion.
constexpr float kPackedRel = 5e-4f;

void expect_near_rel(vec3 a, vec3 b, float rel, const std::string& where) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], rel * std::max(std::fabs(b[c]), 1e-3f)) << where << " channel " << c;
}

// Two flat regions of different light split at column `edge`, with a depth step or a crease (a
// normal step) between them: no filtered pixel crosses to the other side, each region's mean
// stays within 1% and its noise goes down. `indirect`: the light is indirect light (filtered at
// the denoiser's default half resolution), else direct light.
void expect_sharp_edge(const GBuffer& g, int edge = 16, bool indirect = false) {
  const int w = g.width, h = g.height;
  Pcg32 rng(7);
  const Image light = noisy(w, h, rng, 0.3f, [edge](int x, int) { return x < edge ? 1.0f : 4.0f; });
  Denoiser d;
  const Image constant(w, h, vec3(1.0f));
  const Image out = indirect ? run(d, g, HistoryState::kReset, constant, &light).indirect
                             : run(d, g, HistoryState::kReset, light).direct;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // The inputs lie in [0.7, 1.3] and [2.8, 5.2]: a blurred edge would leave that.
      if (x < edge)
        EXPECT_LT(out.at(x, y).x, 1.3f) << x << "," << y;
      else
        EXPECT_GT(out.at(x, y).x, 2.8f) << x << "," << y;
    }
  }
  for (const auto& [x0, x1] : {std::pair{0, edge}, std::pair{edge, w}}) {
    EXPECT_NEAR(mean_x(out, x0, x1, 0, h), mean_x(light, x0, x1, 0, h),
                0.01f * mean_x(light, x0, x1, 0, h));
    EXPECT_LT(deviation_x(out, x0, x1, 0, h), 0.5f * deviation_x(light, x0, x1, 0, h));
  }
}

TEST(Denoiser, AtrousKeepsADepthStepSharp) {
  GBuffer g = plane(32, 24);
  for (int y = 0; y < g.height; ++y)
    for (int x = 16; x < g.width; ++x) g.depth[g.view().index(x, y)] = 2.0f;
  expect_sharp_edge(g);
}

TEST(Denoiser, AtrousKeepsACreaseSharp) {
  GBuffer g = plane(32, 24);
  const vec3 tilted = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  for (int y = 0; y < g.height; ++y)
    for (int x = 16; x < g.width; ++x) g.normal[g.view().index(x, y)] = tilted;
  expect_sharp_edge(g);
}

// Indirect light is filtered at half resolution: its edges stay as sharp, whether the edge
// falls between 2x2 blocks (column 16) or through them (column 15).
TEST(Denoiser, HalfResolutionIndirectLightKeepsADepthStepSharp) {
  for (int edge : {16, 15}) {
    GBuffer g = plane(32, 24);
    for (int y = 0; y < g.height; ++y)
      for (int x = edge; x < g.width; ++x) g.depth[g.view().index(x, y)] = 2.0f;
    SCOPED_TRACE(edge);
    expect_sharp_edge(g, edge, true);
  }
}

TEST(Denoiser, HalfResolutionIndirectLightKeepsACreaseSharp) {
  for (int edge : {16, 15}) {
    GBuffer g = plane(32, 24);
    const vec3 tilted = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
    for (int y = 0; y < g.height; ++y)
      for (int x = edge; x < g.width; ++x) g.normal[g.view().index(x, y)] = tilted;
    SCOPED_TRACE(edge);
    expect_sharp_edge(g, edge, true);
  }
}

// Indirect light stops at geometric edges only (sigma_luminance_indirect 0, the default): on a
// flat plane it smooths across a step of its own, which a tight luminance stop keeps (the
// spatial variance around the step is the step's own, a standard deviation of about 0.75).
TEST(Denoiser, IndirectLightStopsAtLuminanceEdgesOnlyWithASigma) {
  const GBuffer g = plane(32, 24);
  const Image light = image_of(32, 24, [](int x, int) { return vec3(x < 16 ? 0.5f : 2.0f); });
  const Image direct(32, 24, vec3(1.0f));
  for (float sigma : {0.0f, 0.05f}) {
    SCOPED_TRACE(sigma);
    Denoiser d;
    d.settings().sigma_luminance_indirect = sigma;
    d.settings().indirect_resolution = 1;
    const Image out = run(d, g, HistoryState::kReset, direct, &light).indirect;
    for (int y = 0; y < 24; ++y) {
      if (sigma == 0.0f) {
        EXPECT_GT(out.at(15, y).x, 0.6f) << y;
        EXPECT_LT(out.at(16, y).x, 1.9f) << y;
      } else {
        EXPECT_NEAR(out.at(15, y).x, 0.5f, 0.005f) << y;
        EXPECT_NEAR(out.at(16, y).x, 2.0f, 0.02f) << y;
      }
    }
  }
}

// Half resolution spreads the same passes twice as far: flat indirect light keeps its mean and
// loses more of its noise than at full resolution.
TEST(Denoiser, HalfResolutionIndirectLightReachesFurther) {
  const GBuffer g = plane(64, 64);
  Pcg32 rng(5);
  const Image light = noisy(64, 64, rng, 0.5f, [](int, int) { return 2.0f; });
  const Image direct(64, 64, vec3(1.0f));
  float deviation[2];
  for (int resolution : {1, 2}) {
    Denoiser d;
    d.settings().indirect_resolution = resolution;
    const Image out = run(d, g, HistoryState::kReset, direct, &light).indirect;
    EXPECT_NEAR(mean_x(out, 0, 64, 0, 64), mean_x(light, 0, 64, 0, 64),
                0.01f * mean_x(light, 0, 64, 0, 64));
    deviation[resolution - 1] = deviation_x(out, 8, 56, 8, 56);
  }
  EXPECT_LT(deviation[1], 0.7f * deviation[0]);
  EXPECT_LT(deviation[0], 0.25f * deviation_x(light, 8, 56, 8, 56));
}

// While the history is short, direct light is filtered at half resolution with one pass fewer:
// it keeps its mean and loses more of its noise than the full-resolution passes take away.
TEST(Denoiser, HalfResolutionDirectLightReachesFurther) {
  const GBuffer g = plane(64, 64);
  Pcg32 rng(9);
  const Image light = noisy(64, 64, rng, 0.5f, [](int, int) { return 2.0f; });
  float deviation[2];
  for (int half : {0, 1}) {
    Denoiser d;
    d.settings().half_direct_frames = half;
    const Image out = run(d, g, HistoryState::kReset, light).direct;
    EXPECT_NEAR(mean_x(out, 0, 64, 0, 64), mean_x(light, 0, 64, 0, 64),
                0.01f * mean_x(light, 0, 64, 0, 64));
    deviation[half] = deviation_x(out, 8, 56, 8, 56);
  }
  EXPECT_LT(deviation[1], 0.8f * deviation[0]);
}

// Direct light goes back to full resolution after half_direct_frames frames since the last
// reset: those frames differ from a denoiser that never halves it, every later frame is the same
// bit for bit (the history holds the unfiltered light), and a reset starts the count again.
TEST(Denoiser, HalfResolutionDirectLightOnlyWhileTheHistoryIsShort) {
  const int n = 24, half_frames = 3;
  const GBuffer g = plane(n, n);
  Pcg32 rng(43);
  Denoiser halved, full;
  halved.settings().half_direct_frames = half_frames;
  full.settings().half_direct_frames = 0;
  for (int k = 0; k < 2 * half_frames + 2; ++k) {
    const Image light = noisy(n, n, rng, 0.5f, [](int, int) { return 1.0f; });
    // A reset at frame 0 and again at frame half_frames + 1.
    const bool reset = k == 0 || k == half_frames + 1;
    const HistoryState state = reset ? HistoryState::kReset : HistoryState::kCameraMoved;
    const Image a = run(halved, g, state, light).direct;
    const Image b = run(full, g, state, light).direct;
    const int since_reset = k <= half_frames ? k : k - half_frames - 1;
    if (since_reset < half_frames)
      EXPECT_NE(a.pixels(), b.pixels()) << "frame " << k;
    else
      EXPECT_EQ(a.pixels(), b.pixels()) << "frame " << k;
  }
}

// While the world changes (a flashlight carried through a level) the history is clipped to each
// frame's neighbourhood, frame after frame, and stays about as noisy as a short one: direct light
// is filtered at half resolution then too, long after the last reset, unless half_direct_frames
// turns half resolution off, and with every pass (after a reset, one fewer).
TEST(Denoiser, HalfResolutionDirectLightWhileTheWorldChanges) {
  DenoiseSettings s;
  s.half_direct_frames = 4;
  const int height = 64, rest_frames = 0, long_ago = 100;
  for (const bool clipped : {false, true}) {
    const denoise::AtrousPlan p =
        denoise::atrous_plan(s, true, true, height, rest_frames, long_ago, clipped);
    EXPECT_EQ(p.direct_half, clipped);
    EXPECT_EQ(p.direct_iterations, s.atrous_iterations);
    // (Every pixel's history is long: the spatial variance stays at full resolution.)
    EXPECT_FALSE(p.half_variance);
  }
  const denoise::AtrousPlan after_reset =
      denoise::atrous_plan(s, true, true, height, rest_frames, 1, false);
  EXPECT_TRUE(after_reset.direct_half);
  EXPECT_EQ(after_reset.direct_iterations, s.atrous_iterations - 1);
  const denoise::AtrousPlan changing_after_reset =
      denoise::atrous_plan(s, true, true, height, rest_frames, 1, true);
  EXPECT_TRUE(changing_after_reset.direct_half);
  EXPECT_EQ(changing_after_reset.direct_iterations, s.atrous_iterations);
  s.half_direct_frames = 0;
  EXPECT_FALSE(
      denoise::atrous_plan(s, true, true, height, rest_frames, long_ago, true).direct_half);

  // The frames themselves: after the first frames, world changes differ from a denoiser that
  // never halves direct light, camera moves do not.
  const int n = 24;
  const GBuffer g = plane(n, n);
  Pcg32 rng(44);
  Denoiser halved, full;
  halved.settings().half_direct_frames = 2;
  full.settings().half_direct_frames = 0;
  for (int k = 0; k < 8; ++k) {
    const Image light = noisy(n, n, rng, 0.5f, [](int, int) { return 1.0f; });
    const HistoryState state = k == 0  ? HistoryState::kReset
                               : k < 5 ? HistoryState::kCameraMoved
                                       : HistoryState::kWorldChanged;
    const Image a = run(halved, g, state, light).direct;
    const Image b = run(full, g, state, light).direct;
    if (k >= 2 && k < 5)
      EXPECT_EQ(a.pixels(), b.pixels()) << "frame " << k;
    else
      EXPECT_NE(a.pixels(), b.pixels()) << "frame " << k;
  }
  // Without temporal reuse there is no history to clip: world changes are filtered as camera
  // moves are.
  Denoiser still_halved, still_full;
  for (Denoiser* d : {&still_halved, &still_full}) d->settings().temporal = false;
  still_halved.settings().half_direct_frames = 2;
  still_full.settings().half_direct_frames = 0;
  for (int k = 0; k < 5; ++k) {
    const Image light = noisy(n, n, rng, 0.5f, [](int, int) { return 1.0f; });
    const HistoryState state = k == 0 ? HistoryState::kReset : HistoryState::kWorldChanged;
    const Image a = run(still_halved, g, state, light).direct;
    const Image b = run(still_full, g, state, light).direct;
    if (k >= 2)
      EXPECT_EQ(a.pixels(), b.pixels()) << "frame " << k;
    else
      EXPECT_NE(a.pixels(), b.pixels()) << "frame " << k;
  }
}

// Direct and indirect light at half resolution share the downsample, the passes they both take
// and the upsample: each comes out as it does when filtered there alone.
TEST(Denoiser, BothLightsAtHalfResolutionMatchEachAlone) {
  GBuffer g = plane(40, 32);
  for (int y = 0; y < g.height; ++y)
    for (int x = 23; x < g.width; ++x) g.depth[g.view().index(x, y)] = 2.0f;
  Pcg32 rng(17);
  const Image direct = noisy(40, 32, rng, 0.5f, [](int x, int) { return x < 23 ? 1.0f : 3.0f; });
  const Image indirect = noisy(40, 32, rng, 0.5f, [](int, int y) { return y < 9 ? 0.5f : 2.0f; });
  for (int indirect_iterations : {1, 2, 4}) {  // fewer, as many and more passes than direct's 2
    SCOPED_TRACE(indirect_iterations);
    Denoiser both, direct_alone, indirect_alone;
    for (Denoiser* d : {&both, &direct_alone, &indirect_alone})
      d->settings().indirect_iterations = indirect_iterations + 4;  // (32 pixels high: 4 fewer)
    indirect_alone.settings().half_direct_frames = 0;
    // Frames 0 to 3 after a reset are filtered with direct light at half resolution. Up to frame
    // 2 the spatial variance is estimated at half resolution too, which takes both lights
    // there: indirect light alone (direct light at full resolution) is compared at frame 3.
    for (int frame = 0; frame < 4; ++frame) {
      SCOPED_TRACE(frame);
      const HistoryState state = frame == 0 ? HistoryState::kReset : HistoryState::kRest;
      const Output out = run(both, g, state, direct, &indirect);
      const Image d = run(direct_alone, g, state, direct).direct;
      const Image i = run(indirect_alone, g, state, direct, &indirect).indirect;
      for (size_t k = 0; k < g.size(); ++k) {
        expect_near_rel(out.direct.pixels()[k], d.pixels()[k], 1e-5f, "direct");
        if (frame == 3) expect_near_rel(out.indirect.pixels()[k], i.pixels()[k], 1e-5f, "indirect");
      }
      // (And the direct light was filtered: it is not its input.)
      EXPECT_NE(out.direct.pixels(), direct.pixels());
    }
  }
}

// While every pixel's history is short and both lights are filtered at half resolution, the
// spatial variance is estimated there: the variance of each texel's mean, a quarter of a
// pixel's. Uniform noise of amplitude a around level m has variance m^2 a^2 / 3.
TEST(Denoiser, SpatialVarianceAtHalfResolutionIsTheBlockMeans) {
  const GBuffer g = plane(64, 64);
  Pcg32 rng(41);
  const Image direct = noisy(64, 64, rng, 0.5f, [](int, int) { return 1.0f; });
  const Image indirect = noisy(64, 64, rng, 0.5f, [](int, int) { return 2.0f; });
  const float pixel_variance = (1.0f + 4.0f) * 0.25f / 3.0f;
  for (int half_direct_frames : {4, 0}) {  // at half resolution, then at full resolution
    SCOPED_TRACE(half_direct_frames);
    Denoiser d;
    d.settings().half_direct_frames = half_direct_frames;
    run(d, g, HistoryState::kReset, direct, &indirect);
    Image view;
    d.debug_view(DenoiseView::kVariance, view);
    const float expected = std::sqrt(pixel_variance / (half_direct_frames > 0 ? 4.0f : 1.0f));
    // Away from the image's border, where boxes are whole.
    EXPECT_NEAR(mean_x(view, 8, 56, 8, 56), expected, 0.05f * expected);
    for (int y = 8; y < 56; ++y)
      for (int x = 8; x < 56; ++x) EXPECT_NEAR(view.at(x, y).x, expected, 0.4f * expected);
  }
}

// At a reset every pixel's history holds its one frame: the block moments read from the light
// equal those read from the history, and the rest of the texel is the same.
TEST(Denoiser, ResetBlockMomentsFromTheLightEqualTheHistorys) {
  constexpr int w = 7, h = 5, hw = 4, hh = 3;  // (odd sizes: clamped blocks at the edges)
  Pcg32 rng(5);
  std::vector<float> depth(w * h), nx(w * h, 0.0f), ny(w * h, 0.0f), nz(w * h, -1.0f);
  std::vector<float> light[2][3];
  std::vector<float> history_planes[8];
  denoise::HistoryPlanes history;
  for (int k = 0; k < 8; ++k) {
    history_planes[k].resize(w * h);
    history.c[k] = history_planes[k].data();
  }
  for (auto& l : light)
    for (auto& c : l) c.resize(w * h);
  for (int i = 0; i < w * h; ++i) {
    depth[i] = i % 5 == 3 ? 0.0f : 1.0f + 0.01f * rng.next_float();  // some pixels see nothing
    vec3 c[2];
    for (int l = 0; l < 2; ++l) {
      c[l] = vec3(rng.next_float(), rng.next_float(), rng.next_float());
      for (int k = 0; k < 3; ++k) light[l][k][i] = c[l][k];
    }
    const float ld = denoise::luminance_of(c[0]), li = denoise::luminance_of(c[1]);
    history.set(size_t(i), {vec4(c[0], ld * ld), vec4(c[1], li * li)});
  }
  const std::vector<float> length(w * h, 0.0f);
  // Per mode: depth, normal, each light's rgb and variance, the five moment sums.
  std::vector<float> out[2][17];
  for (int mode = 0; mode < 2; ++mode) {
    for (auto& o : out[mode]) o.assign(hw * hh, -1.0f);
    denoise::HalfDownsample p;
    p.surface = {depth.data(), nx.data(), ny.data(), nz.data(), nullptr};
    p.lights = 2;
    for (int l = 0; l < 2; ++l) {
      p.light[l] = {light[l][0].data(), light[l][1].data(), light[l][2].data()};
      p.half_light[l] = {out[mode][4 + 4 * l].data(), out[mode][5 + 4 * l].data(),
                         out[mode][6 + 4 * l].data()};
      p.half_variance[l] = out[mode][7 + 4 * l].data();
    }
    p.width = w;
    p.height = h;
    p.half_surface = {out[mode][0].data(), out[mode][1].data(), out[mode][2].data(),
                      out[mode][3].data(), nullptr};
    p.half_width = hw;
    p.moments = mode == 0 ? denoise::BlockMoments::kOneFrame : denoise::BlockMoments::kHistory;
    p.history = mode == 0 ? denoise::ConstHistoryPlanes{} : denoise::ConstHistoryPlanes(history);
    p.length = mode == 0 ? nullptr : length.data();
    p.cap_indirect = 3.0f;
    for (int k = 0; k < 5; ++k) p.half_moments[k] = out[mode][12 + k].data();
    for (int y = 0; y < hh; ++y)
      for (int x = 0; x < hw; ++x) denoise::downsample_pixel(p, x, y);
  }
  // (Equal up to rounding: a compiler may fuse the square into the sum.)
  for (int k = 0; k < 17; ++k)
    for (int t = 0; t < hw * hh; ++t)
      EXPECT_NEAR(out[0][k][size_t(t)], out[1][k][size_t(t)],
                  1e-6f * std::fabs(out[1][k][size_t(t)]))
          << k << " " << t;
  // (Texels with a surface got a variance scale and moments.)
  EXPECT_GT(out[0][7][0], 0.0f);
  EXPECT_GT(out[0][16][0], 0.0f);
}

// The indirect filter's reach follows the image: photon blotches cover a fixed part of the view.
TEST(Denoiser, IndirectPassesFollowTheImageHeight) {
  EXPECT_EQ(indirect_iterations_for(5, 512), 5);
  EXPECT_EQ(indirect_iterations_for(5, 540), 5);
  EXPECT_EQ(indirect_iterations_for(5, 1024), 6);
  EXPECT_EQ(indirect_iterations_for(5, 256), 4);
  EXPECT_EQ(indirect_iterations_for(5, 32), 1);
  EXPECT_EQ(indirect_iterations_for(5, 4), 1);
  EXPECT_EQ(indirect_iterations_for(8, 4096), 8);
  EXPECT_EQ(indirect_iterations_for(0, 512), 0);
}

// A column one pixel wide behind its neighbours has no half-resolution texel of its own (each
// 2x2 block keeps its nearest surface): it keeps its own light rather than borrowing theirs.
TEST(Denoiser, HalfResolutionKeepsASliverItCannotRepresent) {
  GBuffer g = plane(32, 16);
  for (int y = 0; y < 16; ++y) g.depth[g.view().index(15, y)] = 2.0f;
  const Image light = image_of(32, 16, [](int x, int) { return vec3(x == 15 ? 4.0f : 1.0f); });
  const Image direct(32, 16, vec3(1.0f));
  Denoiser d;
  const Image out = run(d, g, HistoryState::kReset, direct, &light).indirect;
  for (int y = 0; y < 16; ++y) {
    EXPECT_NEAR(out.at(15, y).x, 4.0f, 1e-4f) << y;
    EXPECT_NEAR(out.at(14, y).x, 1.0f, 1e-4f) << y;
    EXPECT_NEAR(out.at(16, y).x, 1.0f, 1e-4f) << y;
  }
}

// An emitter's black face (no albedo, no specular) carries no reflected light: its zeros must
// not darken the surface around it, for direct or indirect light (the Cornell box's ceiling
// around its light).
TEST(Denoiser, SurfacesThatReflectNothingDoNotDarkenTheirNeighbours) {
  GBuffer g = plane(32, 32);
  const auto black = [](int x, int y) { return x >= 12 && x < 20 && y >= 12 && y < 20; };
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      if (black(x, y)) g.albedo[g.view().index(x, y)] = vec3(0.0f);
  const Image light =
      image_of(32, 32, [&](int x, int y) { return vec3(black(x, y) ? 0.0f : 1.0f); });
  for (int resolution : {1, 2}) {
    Denoiser d;
    d.settings().indirect_resolution = resolution;
    const Output out = run(d, g, HistoryState::kReset, light, &light);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        if (black(x, y)) continue;
        EXPECT_NEAR(out.direct.at(x, y).x, 1.0f, 1e-4f) << x << "," << y;
        EXPECT_NEAR(out.indirect.at(x, y).x, 1.0f, 1e-4f)
            << x << "," << y << " at 1/" << resolution;
      }
  }
}

TEST(Denoiser, SpatialFilterReducesNoiseOfAFlatRegion) {
  const GBuffer g = plane(32, 32);
  Pcg32 rng(3);
  const Image light = noisy(32, 32, rng, 0.5f, [](int, int) { return 2.0f; });
  Denoiser d;
  const Image out = run(d, g, HistoryState::kReset, light).direct;
  EXPECT_NEAR(mean_x(out, 0, 32, 0, 32), mean_x(light, 0, 32, 0, 32),
              0.01f * mean_x(light, 0, 32, 0, 32));
  EXPECT_LT(deviation_x(out, 0, 32, 0, 32), 0.25f * deviation_x(light, 0, 32, 0, 32));
}

// A textured albedo under constant light comes back as it went in, with the filter on: the
// filter only ever sees the constant (demodulated) light. Emission is set apart and added back.
TEST(Denoiser, DemodulationRoundTripsAlbedo) {
  GBuffer g = plane(20, 20);
  Pcg32 rng(11);
  for (size_t i = 0; i < g.size(); ++i) {
    g.albedo[i] = vec3(0.05f) + 0.9f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
    if (i % 7 == 0) g.emission[i] = vec3(3.0f, 2.0f, 1.0f);
  }
  const vec3 direct_light(0.8f, 0.5f, 0.3f), indirect_light(0.2f, 0.4f, 0.1f);
  const Image direct = image_of(20, 20, [&](int x, int y) {
    const size_t i = g.view().index(x, y);
    return g.albedo[i] * direct_light + g.emission[i];
  });
  const Image indirect = image_of(
      20, 20, [&](int x, int y) { return g.albedo[g.view().index(x, y)] * indirect_light; });
  Denoiser d;
  for (const HistoryState state : {HistoryState::kReset, HistoryState::kRest}) {
    const Output out = run(d, g, state, direct, &indirect);
    for (int y = 0; y < 20; ++y) {
      for (int x = 0; x < 20; ++x) {
        const std::string where = std::to_string(x) + "," + std::to_string(y);
        expect_near_rel(out.direct.at(x, y), direct.at(x, y), 1e-5f, "direct " + where);
        expect_near_rel(out.indirect.at(x, y), indirect.at(x, y), 1e-5f, "indirect " + where);
      }
    }
  }
}

// A dark texture whose blue crosses the albedo floor from pixel to pixel (OpenArena's rubble and
// trims): the filter mixes the pixels' demodulated light, and each gets back about its own
// albedo's share, within the channel floor's (denoise::demodulation_factor). With a black
// channel demodulated by 1, the pixels below the floor took their neighbours' light falling on
// them back undivided: blue specks hundreds of times too bright.
TEST(Denoiser, AChannelAcrossTheAlbedoFloorLeavesNoSpecks) {
  GBuffer g = plane(20, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      g.albedo[g.view().index(x, y)] =
          vec3(0.5f, 0.3f, ((x + y) % 2 == 0 ? 0.5f : 2.0f) * denoise::kAlbedoFloor);
  const vec3 light(0.8f, 0.5f, 0.3f);
  const Image lit =
      image_of(20, 20, [&](int x, int y) { return g.albedo[g.view().index(x, y)] * light; });
  Denoiser d;
  for (const HistoryState state : {HistoryState::kReset, HistoryState::kRest}) {
    const Output out = run(d, g, state, lit, &lit);
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x) {
        const std::string where = std::to_string(x) + "," + std::to_string(y);
        expect_near_rel(vec3(out.direct.at(x, y).x, out.direct.at(x, y).y, 0.0f),
                        vec3(lit.at(x, y).x, lit.at(x, y).y, 0.0f), 1e-5f, where);
        // Blue within the light the channel floor stands for (the blue albedos are 0.5 and 2
        // times the black floor, far below the channel floor).
        const float floor_light = denoise::kChannelFloor * 0.5f * light.z;
        EXPECT_NEAR(out.direct.at(x, y).z, lit.at(x, y).z, floor_light) << where;
        EXPECT_NEAR(out.indirect.at(x, y).z, lit.at(x, y).z, floor_light) << where;
      }
  }
}

// At rest the history is a plain running average: N frames of independent noise come out as
// their exact mean (no cap on the history), direct and per-frame indirect alike.
TEST(Denoiser, FramesAtRestAverageToTheirExactMean) {
  const int w = 8, h = 8, frames = 40;
  GBuffer g = plane(w, h);
  Pcg32 rng(5);
  for (size_t i = 0; i < g.size(); ++i)
    g.albedo[i] = vec3(0.2f) + 0.8f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  Denoiser d;
  d.settings().spatial = false;
  d.settings().history_max = 4;  // a cap that must not apply at rest
  std::vector<vec3> sum_d(g.size(), vec3(0.0f)), sum_i(g.size(), vec3(0.0f));
  Output out;
  for (int k = 0; k < frames; ++k) {
    const Image direct = noisy(w, h, rng, 0.9f, [](int, int) { return 1.0f; });
    const Image indirect = noisy(w, h, rng, 0.9f, [](int x, int) { return 0.1f * float(x); });
    for (size_t i = 0; i < g.size(); ++i) {
      sum_d[i] += direct.pixels()[i];
      sum_i[i] += indirect.pixels()[i];
    }
    out = run(d, g, k == 0 ? HistoryState::kReset : HistoryState::kRest, direct, &indirect);
  }
  for (size_t i = 0; i < g.size(); ++i) {
    expect_near_rel(out.direct.pixels()[i], sum_d[i] / float(frames), 1e-5f, "direct");
    expect_near_rel(out.indirect.pixels()[i], sum_i[i] / float(frames), 1e-5f, "indirect");
    EXPECT_EQ(d.history_length()[i], float(frames - 1));
  }
}

// Jittered frames at rest see several surfaces in an edge pixel: the emission (and the albedo)
// are averaged with the light, so the pixel converges to the average of what it saw.
TEST(Denoiser, EmissionSeenAtRestIsAveragedWithTheFrames) {
  const int w = 4, h = 4, frames = 6;
  Denoiser d;
  d.settings().spatial = false;
  vec3 sum(0.0f);
  Output out;
  for (int k = 0; k < frames; ++k) {
    GBuffer g = plane(w, h);
    const vec3 emission = k % 2 ? vec3(10.0f, 5.0f, 1.0f) : vec3(0.0f);
    for (vec3& e : g.emission) e = emission;
    const Image direct = image_of(w, h, [&](int, int) { return vec3(0.5f) + emission; });
    sum += direct.at(1, 1);
    out = run(d, g, k == 0 ? HistoryState::kReset : HistoryState::kRest, direct);
  }
  expect_near_rel(out.direct.at(1, 1), sum / float(frames), 1e-5f, "edge pixel");
}

// Frames that all restart the history (accumulation off) skip the rest averages a reset would
// start for a later frame: the frames are the same bytes. Half of the image is an emitter with
// albedo varying across it, where the rest average's factor and emission would enter.
TEST(Denoiser, ResetsWhoseHistoryNoFrameContinuesGiveTheSameFrames) {
  const int w = 24, h = 16;
  Denoiser kept, dropped;
  Pcg32 rng(7, 1);
  for (int k = 0; k < 3; ++k) {
    GBuffer g = plane(w, h);
    for (int i = 0; i < w * h; ++i) {
      g.albedo[size_t(i)] = vec3(0.2f + 0.6f * float(i % w) / float(w), 0.5f, 0.3f);
      if (i % w < w / 2) g.emission[size_t(i)] = vec3(2.0f, 1.0f, 0.5f);
    }
    const Image direct = noisy(w, h, rng, 0.5f, [](int, int) { return 1.0f; });
    const Image indirect = noisy(w, h, rng, 0.8f, [](int, int) { return 0.3f; });
    StageTimes times;
    Output a{direct, indirect}, b{direct, indirect};
    kept.run({g, HistoryState::kReset, IndirectHistory::kPerFrame, times, true}, a.direct,
             &a.indirect);
    dropped.run({g, HistoryState::kReset, IndirectHistory::kPerFrame, times, false}, b.direct,
                &b.indirect);
    ASSERT_EQ(a.direct.pixels(), b.direct.pixels()) << k;
    ASSERT_EQ(a.indirect.pixels(), b.indirect.pixels()) << k;
  }
}

// Indirect light a technique accumulates itself keeps a short history: accumulated_history
// frames while the camera moves, one at rest (the technique's own average is the history there).
TEST(Denoiser, AccumulatedIndirectLightKeepsItsCap) {
  const GBuffer g = plane(4, 4);
  for (const HistoryState state : {HistoryState::kRest, HistoryState::kCameraMoved}) {
    Denoiser d;
    d.settings().spatial = false;
    d.settings().accumulated_history = 3;
    const int cap = state == HistoryState::kRest ? 1 : 3;
    float expected_d = 0.0f, expected_i = 0.0f;
    Output out;
    for (int k = 0; k < 8; ++k) {
      const float v = float(k * k);
      const Image light = image_of(4, 4, [&](int, int) { return vec3(v); });
      out = run(d, g, k == 0 ? HistoryState::kReset : state, light, &light,
                IndirectHistory::kAccumulated);
      // Direct: the mean of all frames; indirect: alpha = 1 / (min(n, cap) + 1).
      expected_d += (v - expected_d) / float(k + 1);
      expected_i += (v - expected_i) / float(std::min(k, cap) + 1);
    }
    EXPECT_NEAR(out.direct.at(2, 2).x, expected_d, 1e-4f * expected_d);
    EXPECT_NEAR(out.indirect.at(2, 2).x, expected_i, 1e-4f * expected_i) << cap;
  }
}

// A change of size (the viewer's resolution scaler) keeps the history: it is reprojected from
// the previous size, with motion in the new frame's pixels.
TEST(Denoiser, HistorySurvivesAChangeOfSize) {
  const GBuffer big = plane(16, 16), small = plane(8, 8);
  Denoiser d;
  d.settings().spatial = false;
  for (int k = 0; k < 4; ++k)
    run(d, big, k == 0 ? HistoryState::kReset : HistoryState::kCameraMoved,
        Image(16, 16, vec3(1.0f)));
  const Output out = run(d, small, HistoryState::kCameraMoved, Image(8, 8, vec3(3.0f)));
  // History lengths 0, 1, 2, 3 at the large size; the small frame counts 4: alpha = 1/5.
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_NEAR(out.direct.at(x, y).x, 1.0f + 2.0f / 5.0f, 1e-4f) << x << "," << y;
      EXPECT_EQ(d.history_length()[size_t(y * 8 + x)], 4.0f);
    }
}

// Motion while the camera moves: the history is capped at history_max.
TEST(Denoiser, HistoryIsCappedWhileTheCameraMoves) {
  const GBuffer g = plane(4, 4);
  Denoiser d;
  d.settings().spatial = false;
  d.settings().history_max = 3;
  float expected = 0.0f;
  Output out;
  for (int k = 0; k < 8; ++k) {
    const float v = float(k);
    out = run(d, g, k == 0 ? HistoryState::kReset : HistoryState::kCameraMoved,
              image_of(4, 4, [&](int, int) { return vec3(v); }));
    expected += (v - expected) / float(std::min(k, 3) + 1);
    EXPECT_EQ(d.history_length()[5], float(std::min(k, 3)));
  }
  EXPECT_NEAR(out.direct.at(1, 1).x, expected, 1e-5f);
}

// While the world changes the cap is changing_history_max (at most history_max), and each frame
// that only the camera moves in gets history_max again: a moving light's history stays short.
TEST(Denoiser, HistoryIsCappedShorterWhileTheWorldChanges) {
  const GBuffer g = plane(4, 4);
  for (const auto& [history_max, changing, cap] :
       {std::tuple{6, 2, 2}, std::tuple{6, 4, 4}, std::tuple{3, 5, 3}}) {
    SCOPED_TRACE(std::to_string(history_max) + " " + std::to_string(changing));
    Denoiser d;
    d.settings().spatial = false;
    d.settings().history_max = history_max;
    d.settings().changing_history_max = changing;
    float expected = 0.0f, length = 0.0f;
    Output out;
    // Eight frames of a world that changes, then eight of camera moves.
    for (int k = 0; k < 16; ++k) {
      const float v = float(k % 5);
      const HistoryState state = k == 0  ? HistoryState::kReset
                                 : k < 8 ? HistoryState::kWorldChanged
                                         : HistoryState::kCameraMoved;
      out = run(d, g, state, image_of(4, 4, [&](int, int) { return vec3(v); }));
      length = k == 0 ? 0.0f : std::min(length + 1.0f, float(k < 8 ? cap : history_max));
      EXPECT_EQ(d.history_length()[5], length) << "frame " << k;
      // (A uniform frame's neighbourhood clips the history to its own value.)
      expected = k < 8 ? v : expected + (v - expected) / (length + 1.0f);
    }
    EXPECT_NEAR(out.direct.at(1, 1).x, expected, 1e-4f);
  }
}

// Exact light (DenoiseFrame::exact: a moving spot's, shaded apart) joins the emission: a beam
// moving a pixel a frame across a textured plane shows where it is, its history clamped to the
// range of this frame's light around each pixel, demodulated: inside the beam and well outside
// it exactly this frame's light; only at its two edges, where the range holds both lit and unlit
// light, are last frame's and this frame's averaged (what antialiases a jittered edge).
TEST(Denoiser, ExactLightIsClampedToItsNeighbourhood) {
  const int w = 24, h = 6, beam = 8;
  GBuffer g = plane(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) g.albedo[g.view().index(x, y)] = vec3(0.3f + 0.1f * float(x % 5));
  Denoiser d;
  d.settings().spatial = false;
  const Image direct = image_of(w, h, [](int, int) { return vec3(0.0f); });
  Image out;
  int first = 0;
  for (int k = 0; k < 6; ++k) {
    first = 2 + k;
    const Image exact = image_of(w, h, [&](int x, int y) {
      return x >= first && x < first + beam ? 2.0f * g.albedo[g.view().index(x, y)] : vec3(0.0f);
    });
    StageTimes times;
    out = direct;
    DenoiseFrame frame{g, k == 0 ? HistoryState::kReset : HistoryState::kWorldChanged,
                       IndirectHistory::kPerFrame, times};
    frame.exact = &exact;
    d.run(frame, out, nullptr);
    for (int x = 0; x < w; ++x) {
      const vec3 want = exact.at(x, 2);
      if (k > 0 && (x == first - 1 || x == first + beam - 1)) {
        // Half last frame's, half this frame's (modulation_alpha 0.5): one lit, one not.
        expect_near_rel(out.at(x, 2), 0.5f * 2.0f * g.albedo[g.view().index(x, 2)], kPackedRel,
                        "edge pixel " + std::to_string(x));
        continue;
      }
      expect_near_rel(out.at(x, 2), want, kPackedRel, "pixel " + std::to_string(x));
    }
  }
}

// The world as the camera sees it: a slanted wall (object 0) whose texel (u, v) shows at pixel
// (u + shift.x, v + shift.y).
struct World {
  static constexpr int kW = 24, kH = 16;
  static float depth(int u, int v) { return 2.0f + 0.01f * float(u) + 0.005f * float(v); }
  static GBuffer seen_from(ivec2 shift) {
    GBuffer g = plane(kW, kH);
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        const size_t i = g.view().index(x, y);
        g.depth[i] = depth(x - shift.x, y - shift.y);
        g.albedo[i] = vec3(0.5f + 0.02f * float((x - shift.x + 100) % 7));
        g.motion[i] = vec2(shift);
      }
    }
    return g;
  }
};

// A camera move by whole pixels: each pixel's history is last frame's value where its surface
// was, and pixels whose surface was out of view or hidden by another object start again.
TEST(Denoiser, ReprojectionFollowsTheSurfaceAndDetectsDisocclusion) {
  const int w = World::kW, h = World::kH;
  GBuffer before = World::seen_from(ivec2(0));
  // Last frame, an object (id 1) in front covered pixels [4, 8) x [4, 8), and a part of the wall
  // itself was elsewhere (same id, another depth) at [12, 16) x [8, 12).
  for (int y = 4; y < 8; ++y)
    for (int x = 4; x < 8; ++x) {
      const size_t i = before.view().index(x, y);
      before.mesh[i] = 1;
      before.depth[i] = 1.0f;
    }
  for (int y = 8; y < 12; ++y)
    for (int x = 12; x < 16; ++x) before.depth[before.view().index(x, y)] = 1.0f;
  const ivec2 shift(3, -2);
  const GBuffer after = World::seen_from(shift);

  Pcg32 rng(9);
  const Image light1 = image_of(w, h, [&](int x, int y) {
    return before.albedo[before.view().index(x, y)] * vec3(1.0f + rng.next_float());
  });
  const Image light2 = image_of(w, h, [&](int x, int y) {
    return after.albedo[after.view().index(x, y)] * vec3(1.0f + rng.next_float());
  });
  Denoiser d;
  d.settings().spatial = false;
  run(d, before, HistoryState::kReset, light1);
  const Image out = run(d, after, HistoryState::kCameraMoved, light2).direct;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::string where = std::to_string(x) + "," + std::to_string(y);
      const int sx = x - shift.x, sy = y - shift.y;
      const bool in_view = sx >= 0 && sy >= 0 && sx < w && sy < h;
      const bool covered = in_view && sx >= 4 && sx < 8 && sy >= 4 && sy < 8;
      const bool moved = in_view && sx >= 12 && sx < 16 && sy >= 8 && sy < 12;
      const float length = d.history_length()[after.view().index(x, y)];
      if (!in_view || covered || moved) {
        EXPECT_EQ(length, 0.0f) << where;
        expect_near_rel(out.at(x, y), light2.at(x, y), kPackedRel, where);
      } else {
        EXPECT_EQ(length, 1.0f) << where;
        // Demodulated by the albedo the surface had then and has now (the same texel).
        expect_near_rel(out.at(x, y), 0.5f * (light1.at(sx, sy) + light2.at(x, y)), kPackedRel,
                        where);
      }
    }
  }
}

// In motion the light is remodulated with an albedo factor and emission averaged with last
// frame's where the pixel saw the same surface (temporal_blend; modulation_alpha 0.5):
// jittered frames see other texels of a texture, and two of them come closer to the pixel's
// average than one. Where last frame saw no part of this surface (out of view, or another depth)
// the pixel takes this frame's alone, and modulation_alpha 1 turns the averaging off.
TEST(Denoiser, InMotionTheAlbedoAndEmissionAreAveragedOnTheSameSurface) {
  const int w = 12, h = 6;
  auto albedo = [](int x, int y, int frame) {
    return vec3(0.2f + 0.05f * float(x), 0.3f + 0.1f * float(y), frame == 0 ? 0.9f : 0.4f);
  };
  auto emission = [](int x, int, int frame) {
    return x % 3 == 0 ? vec3(frame == 0 ? 4.0f : 2.0f, 1.0f, 0.0f) : vec3(0.0f);
  };
  const float light = 0.7f;
  // The camera moved two pixels: this frame's pixel x saw its surface at x - 2. Last frame the
  // wall at [6, 8) x [2, 4) (of last frame's pixels) was at another depth.
  const ivec2 shift(2, 0);
  GBuffer before = plane(w, h), after = plane(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = before.view().index(x, y);
      before.albedo[i] = albedo(x - shift.x, y, 0);
      before.emission[i] = emission(x - shift.x, y, 0);
      if (x >= 6 && x < 8 && y >= 2 && y < 4) before.depth[i] = 2.0f;
      after.albedo[i] = albedo(x - 2 * shift.x, y, 1);
      after.emission[i] = emission(x - 2 * shift.x, y, 1);
      after.motion[i] = vec2(shift);
    }
  auto frame_of = [&](const GBuffer& g) {
    return image_of(w, h, [&](int x, int y) {
      const size_t i = g.view().index(x, y);
      return light * g.albedo[i] + g.emission[i];
    });
  };
  for (const float alpha : {0.5f, 1.0f}) {
    Denoiser d;
    d.settings().spatial = false;
    d.settings().modulation_alpha = alpha;
    run(d, before, HistoryState::kReset, frame_of(before));
    const Image out = run(d, after, HistoryState::kCameraMoved, frame_of(after)).direct;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::string where =
            std::to_string(x) + "," + std::to_string(y) + " alpha " + std::to_string(alpha);
        const size_t i = after.view().index(x, y);
        const int sx = x - shift.x;
        const bool kept = sx >= 0 && !(sx >= 6 && sx < 8 && y >= 2 && y < 4);
        const size_t q = before.view().index(std::max(sx, 0), y);
        const float a = kept ? alpha : 1.0f;
        const vec3 f = before.albedo[q] + (after.albedo[i] - before.albedo[q]) * a;
        const vec3 e = before.emission[q] + (after.emission[i] - before.emission[q]) * a;
        expect_near_rel(out.at(x, y), light * f + e, kPackedRel, where);
      }
  }
}

// Sub-pixel motion reads last frame's light bilinearly: a ramp is interpolated exactly.
TEST(Denoiser, SubPixelMotionInterpolatesBilinearly) {
  const int w = 16, h = 8;
  const GBuffer before = plane(w, h);
  GBuffer after = plane(w, h);
  for (vec2& m : after.motion) m = vec2(0.25f, 0.5f);
  const Image ramp = image_of(w, h, [](int x, int y) { return vec3(float(x) + 10.0f * y); });
  const Image flat = image_of(w, h, [](int, int) { return vec3(1.0f); });
  Denoiser d;
  d.settings().spatial = false;
  run(d, before, HistoryState::kReset, ramp);
  const Image out = run(d, after, HistoryState::kCameraMoved, flat).direct;
  for (int y = 1; y < h; ++y) {
    for (int x = 1; x < w; ++x) {
      const float history = float(x) - 0.25f + 10.0f * (float(y) - 0.5f);
      EXPECT_NEAR(out.at(x, y).x, 0.5f * (history + 1.0f), 1e-4f) << x << "," << y;
    }
  }
}

// At rest the motion is zero: each pixel reads its own history, not a blend of neighbours.
TEST(Denoiser, ZeroMotionReadsTheSamePixel) {
  const GBuffer g = plane(8, 8);
  Pcg32 rng(4);
  const Image a = noisy(8, 8, rng, 0.9f, [](int, int) { return 1.0f; });
  const Image b = noisy(8, 8, rng, 0.9f, [](int, int) { return 1.0f; });
  for (const HistoryState state : {HistoryState::kRest, HistoryState::kCameraMoved}) {
    Denoiser d;
    d.settings().spatial = false;
    run(d, g, HistoryState::kReset, a);
    const Image out = run(d, g, state, b).direct;
    for (size_t i = 0; i < g.size(); ++i)
      EXPECT_NEAR(out.pixels()[i].x, 0.5f * (a.pixels()[i].x + b.pixels()[i].x), 1e-6f);
  }
}

// When the world changed, a history far outside this frame's neighbourhood (of the pixels with a
// surface) is clamped into its mean +- clip_gamma sigma before blending; a camera move alone
// keeps it. Some pixels show no surface: they pass through, and no neighbourhood counts them.
TEST(Denoiser, WorldChangesClipTheHistoryToTheNeighbourhood) {
  const int n = 12;
  GBuffer g = plane(n, n);
  const auto hole = [](int x, int y) { return (x + 2 * y) % 5 == 0; };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      if (!hole(x, y)) continue;
      const size_t i = g.view().index(x, y);
      g.primitive[i] = g.mesh[i] = kNoPrimitive;
      g.normal[i] = g.geometric_normal[i] = vec3(0.0f);
      g.albedo[i] = vec3(0.0f);
    }
  const Image old_light = image_of(n, n, [](int, int) { return vec3(100.0f); });
  Pcg32 rng(13);
  const Image light = image_of(n, n, [&](int, int) {
    return vec3(1.0f) + 0.2f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  });
  for (const HistoryState state : {HistoryState::kWorldChanged, HistoryState::kCameraMoved}) {
    Denoiser d;
    d.settings().spatial = false;
    const float gamma = d.settings().clip_gamma;
    run(d, g, HistoryState::kReset, old_light);
    const Image out = run(d, g, state, light).direct;
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        if (hole(x, y)) {
          EXPECT_EQ(out.at(x, y), light.at(x, y)) << x << "," << y;
          continue;
        }
        vec3 history(100.0f);
        if (state == HistoryState::kWorldChanged) {
          vec3 s1(0.0f), s2(0.0f);
          float count = 0.0f;
          for (int qy = std::max(y - 1, 0); qy <= std::min(y + 1, n - 1); ++qy)
            for (int qx = std::max(x - 1, 0); qx <= std::min(x + 1, n - 1); ++qx) {
              if (hole(qx, qy)) continue;
              s1 += light.at(qx, qy);
              s2 += light.at(qx, qy) * light.at(qx, qy);
              count += 1.0f;
            }
          const vec3 mean = s1 / count;
          const vec3 sigma = glm::sqrt(glm::max(s2 / count - mean * mean, vec3(0.0f)));
          history = glm::min(history, mean + gamma * sigma);
          EXPECT_LT(history.x, 1.5f);
        }
        expect_near_rel(out.at(x, y), 0.5f * (history + light.at(x, y)), 1e-4f,
                        std::to_string(x) + "," + std::to_string(y));
      }
    }
  }
}

// When nothing but a spot light changed, direct light's history is clipped only in the region
// its cones reach (LightChangeRegion), and kept elsewhere: a flashlight's move leaves the still
// lights' averages alone. Indirect light's history is clipped everywhere (bounced light reaches
// beyond the cone).
TEST(Denoiser, ASpotLightsChangeClipsDirectLightOnlyInItsCone) {
  const int n = 12;
  const GBuffer g = plane(n, n);  // pixel (x, y) sees the point (x, y, 1)
  // A cone from (6, 5.5, 1) along -x, 80 degrees wide: columns 0 to 5 are inside, 6 to 11 not.
  LightChangeRegion cone = LightChangeRegion::none();
  cone.cones = 1;
  cone.apex[0] = vec3(6.0f, 5.5f, 1.0f);
  cone.axis[0] = vec3(-1.0f, 0.0f, 0.0f);
  cone.cos_outer[0] = std::cos(glm::radians(80.0f));
  const Image old_light = image_of(n, n, [](int, int) { return vec3(100.0f); });
  Pcg32 rng(19);
  const Image light = image_of(n, n, [&](int, int) {
    return vec3(1.0f) + 0.2f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  });
  Denoiser d;
  d.settings().spatial = false;
  StageTimes times;
  Image direct = old_light, indirect = old_light;
  d.run({g, HistoryState::kReset, IndirectHistory::kPerFrame, times}, direct, &indirect);
  direct = light;
  indirect = light;
  d.run({g, HistoryState::kWorldChanged, IndirectHistory::kPerFrame, times, true, cone}, direct,
        &indirect);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::string where = std::to_string(x) + "," + std::to_string(y);
      EXPECT_EQ(cone.contains(g.position[g.view().index(x, y)]), x < 6) << where;
      if (x < 6)
        EXPECT_LT(direct.at(x, y).x, 1.5f) << where;
      else
        expect_near_rel(direct.at(x, y), 0.5f * (vec3(100.0f) + light.at(x, y)), 1e-4f, where);
      EXPECT_LT(indirect.at(x, y).x, 1.5f) << where;
    }
  }
}

// A region of no cones (a flashlight shaded apart moved: the history's lights did not change)
// clips no direct light: the same frames as a cone that reaches no pixel, direct light's history
// kept everywhere, indirect light's clipped everywhere.
TEST(Denoiser, ARegionOfNoConesClipsNoDirectLight) {
  const int n = 12;
  const GBuffer g = plane(n, n);                       // pixel (x, y) sees the point (x, y, 1)
  LightChangeRegion away = LightChangeRegion::none();  // a narrow cone facing away from the plane
  away.cones = 1;
  away.apex[0] = vec3(6.0f, 5.5f, 0.0f);
  away.axis[0] = vec3(0.0f, 0.0f, -1.0f);
  away.cos_outer[0] = std::cos(glm::radians(10.0f));
  const Image old_light = image_of(n, n, [](int, int) { return vec3(100.0f); });
  Pcg32 rng(23);
  const Image light = image_of(n, n, [&](int, int) {
    return vec3(1.0f) + 0.2f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  });
  Output frames[2];
  const LightChangeRegion regions[2] = {LightChangeRegion::none(), away};
  for (int r = 0; r < 2; ++r) {
    Denoiser d;
    d.settings().spatial = false;
    StageTimes times;
    Image direct = old_light, indirect = old_light;
    d.run({g, HistoryState::kReset, IndirectHistory::kPerFrame, times}, direct, &indirect);
    frames[r] = {light, light};
    d.run({g, HistoryState::kWorldChanged, IndirectHistory::kPerFrame, times, true, regions[r]},
          frames[r].direct, &frames[r].indirect);
  }
  EXPECT_EQ(frames[0].direct.pixels(), frames[1].direct.pixels());
  EXPECT_EQ(frames[0].indirect.pixels(), frames[1].indirect.pixels());
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::string where = std::to_string(x) + "," + std::to_string(y);
      expect_near_rel(frames[0].direct.at(x, y), 0.5f * (vec3(100.0f) + light.at(x, y)), 1e-4f,
                      where);
      EXPECT_LT(frames[0].indirect.at(x, y).x, 1.5f) << where;
    }
}

// Indirect light from a technique's ring of frames (IndirectHistory::kRing) keeps no history
// while the world changes, this frame's light exactly, and keeps one again while only the camera
// moves; per-frame indirect light keeps its clipped history.
TEST(Denoiser, IndirectLightFromARingKeepsNoHistoryWhileTheWorldChanges) {
  const int n = 12;
  const GBuffer g = plane(n, n);
  const Image old_light = image_of(n, n, [](int, int) { return vec3(100.0f); });
  Pcg32 rng(29);
  auto noisy = [&] {
    return image_of(n, n, [&](int, int) {
      return vec3(1.0f) + 0.2f * vec3(rng.next_float(), rng.next_float(), rng.next_float());
    });
  };
  const Image light = noisy(), moved = noisy();
  for (const IndirectHistory history : {IndirectHistory::kRing, IndirectHistory::kPerFrame}) {
    Denoiser d;
    d.settings().spatial = false;
    StageTimes times;
    Image direct = old_light, indirect = old_light;
    d.run({g, HistoryState::kReset, history, times}, direct, &indirect);
    direct = light;
    indirect = light;
    d.run({g, HistoryState::kWorldChanged, history, times, true, LightChangeRegion::none()}, direct,
          &indirect);
    Image direct2 = moved, indirect2 = moved;
    d.run({g, HistoryState::kCameraMoved, history, times}, direct2, &indirect2);
    const bool ring = history == IndirectHistory::kRing;
    float off = 0.0f;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const std::string where =
            std::to_string(x) + "," + std::to_string(y) + (ring ? " ring" : "");
        // Direct light keeps its history (no cone changed) either way.
        expect_near_rel(direct.at(x, y), 0.5f * (vec3(100.0f) + light.at(x, y)), 1e-4f, where);
        if (ring) {
          expect_near_rel(indirect.at(x, y), light.at(x, y), 1e-5f, where);
          // The camera moved: history lengths 0, 1, then 2 (alpha 1/3) from this light.
          expect_near_rel(indirect2.at(x, y),
                          light.at(x, y) + (moved.at(x, y) - light.at(x, y)) / 3.0f, 1e-4f, where);
        } else {
          off += std::fabs(indirect.at(x, y).x - light.at(x, y).x);
        }
      }
    // Per-frame light: the old light's history, clipped into this frame's neighbourhood, still
    // weighs half (about 0.03 from this frame's light on average).
    if (!ring) {
      EXPECT_GT(off / float(n * n), 0.01f);
    }
  }
}

// Background and lights seen directly (no surface) pass through untouched while anything moves;
// at rest they average their frames like every pixel (a jittered edge pixel sees a surface in
// some frames and none in others, and its average must count both).
TEST(Denoiser, PixelsWithoutASurfacePassThroughInMotionAndAverageAtRest) {
  GBuffer g = plane(12, 12);
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 4; ++x) {
      const size_t i = g.view().index(x, y);
      g.primitive[i] = g.mesh[i] = kNoPrimitive;
      g.depth[i] = x == 0 ? std::numeric_limits<float>::infinity() : 3.0f;
      g.normal[i] = g.geometric_normal[i] = vec3(0.0f);
      g.albedo[i] = vec3(0.0f);
      g.emission[i] = x == 0 ? vec3(0.0f) : vec3(40.0f, 30.0f, 20.0f);
    }
  }
  Pcg32 rng(17);
  Denoiser d;
  Image last_indirect;
  for (const HistoryState state :
       {HistoryState::kReset, HistoryState::kCameraMoved, HistoryState::kRest}) {
    const Image direct = image_of(12, 12, [&](int x, int) {
      return x == 0 ? vec3(0.0f) : x < 4 ? vec3(40.0f, 30.0f, 20.0f) : vec3(rng.next_float());
    });
    const Image indirect = image_of(12, 12, [&](int, int) { return vec3(rng.next_float()); });
    const Output out = run(d, g, state, direct, &indirect);
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 4; ++x) {
        EXPECT_EQ(out.direct.at(x, y), direct.at(x, y)) << x << "," << y;
        if (state == HistoryState::kRest) {
          // The second frame of an average that started with the frame before.
          expect_near_rel(out.indirect.at(x, y),
                          0.5f * (indirect.at(x, y) + last_indirect.at(x, y)), 1e-5f,
                          std::to_string(x) + "," + std::to_string(y));
          EXPECT_EQ(d.history_length()[g.view().index(x, y)], 1.0f);
        } else {
          EXPECT_EQ(out.indirect.at(x, y), indirect.at(x, y)) << x << "," << y;
          EXPECT_EQ(d.history_length()[g.view().index(x, y)], 0.0f);
        }
      }
      // Lit pixels are filtered, and the bright light beside them does not leak in.
      for (int x = 4; x < 12; ++x) EXPECT_LT(out.direct.at(x, y).x, 1.0f) << x << "," << y;
    }
    last_indirect = indirect;
  }
}

// A jittered edge pixel at rest sees a surface in some frames and the background in others:
// its average counts every frame, as the raw pipeline's does.
TEST(Denoiser, EdgePixelsAtRestAverageFramesWithAndWithoutASurface) {
  const GBuffer lit = plane(4, 4);
  GBuffer empty = plane(4, 4);
  for (size_t i = 0; i < 16; ++i) {
    empty.primitive[i] = empty.mesh[i] = kNoPrimitive;
    empty.depth[i] = std::numeric_limits<float>::infinity();
    empty.albedo[i] = vec3(0.0f);
  }
  Denoiser d;
  d.settings().spatial = false;
  Output out;
  float expected = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const bool surface = k % 2 == 0;
    const float v = surface ? 2.0f : 0.0f;
    out = run(d, surface ? lit : empty, k == 0 ? HistoryState::kReset : HistoryState::kRest,
              Image(4, 4, vec3(v)));
    expected += (v - expected) / float(k + 1);
  }
  EXPECT_NEAR(out.direct.at(1, 1).x, expected, 1e-5f);
  EXPECT_NEAR(expected, 1.0f, 1e-6f);
}

// Spatial off leaves a single frame as it came; temporal off forgets every earlier frame.
TEST(Denoiser, SwitchesTurnTheirPartOff) {
  GBuffer g = plane(16, 16);
  Pcg32 rng(21);
  for (vec3& a : g.albedo) a = vec3(0.1f) + 0.9f * vec3(rng.next_float());
  const Image first = noisy(16, 16, rng, 0.8f, [](int, int) { return 1.0f; });
  const Image second = noisy(16, 16, rng, 0.8f, [](int, int) { return 1.0f; });
  {
    Denoiser d;
    d.settings().spatial = false;
    const Image out = run(d, g, HistoryState::kReset, first).direct;
    for (size_t i = 0; i < g.size(); ++i)
      expect_near_rel(out.pixels()[i], first.pixels()[i], 1e-6f, "spatial off");
    d.settings().spatial = true;
    d.settings().atrous_iterations = 0;  // no pass is the same as no filter
    const Image none = run(d, g, HistoryState::kReset, first).direct;
    for (size_t i = 0; i < g.size(); ++i)
      expect_near_rel(none.pixels()[i], first.pixels()[i], 1e-6f, "no iterations");
  }
  {
    Denoiser d;
    const Image out = run(d, g, HistoryState::kReset, first).direct;
    float changed = 0.0f;
    for (size_t i = 0; i < g.size(); ++i)
      changed = std::max(changed, std::fabs(out.pixels()[i].x - first.pixels()[i].x));
    EXPECT_GT(changed, 0.1f);
  }
  {
    Denoiser d;
    d.settings().temporal = false;
    d.settings().spatial = false;
    run(d, g, HistoryState::kReset, first);
    const Image out = run(d, g, HistoryState::kRest, second).direct;
    for (size_t i = 0; i < g.size(); ++i) {
      expect_near_rel(out.pixels()[i], second.pixels()[i], 1e-6f, "temporal off");
      EXPECT_EQ(d.history_length()[i], 0.0f);
    }
  }
}

// As frames at rest accumulate, the variance of their mean falls and the filter lets go: a
// pixel-sized checkerboard of light (real detail, not noise) that the first frame's filter blurs
// comes back, and the output stays within the noise of the plain per-pixel average (whose
// relative standard deviation after 64 frames is 0.3 / sqrt(3 * 64) = 2.2%).
TEST(Denoiser, FilterFadesAsTheHistoryGrows) {
  const int n = 16, frames = 64;
  const GBuffer g = plane(n, n);
  Pcg32 rng(23);
  auto level = [](int x, int y) { return (x + y) % 2 ? 1.0f : 1.5f; };
  Denoiser d;
  std::vector<float> sum(g.size(), 0.0f);
  // Mean relative difference to the true light, and to the average of the frames so far.
  auto errors = [&](const Image& out, int count) {
    float truth = 0.0f, average = 0.0f;
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const float v = out.at(x, y).x;
        truth += std::fabs(v - level(x, y)) / level(x, y);
        average += std::fabs(v - sum[g.view().index(x, y)] / float(count)) / level(x, y);
      }
    }
    return std::pair{truth / float(n * n), average / float(n * n)};
  };
  for (int k = 0; k < frames; ++k) {
    const Image light = noisy(n, n, rng, 0.3f, level);
    for (size_t i = 0; i < g.size(); ++i) sum[i] += light.pixels()[i].x;
    const Image out = run(d, g, k == 0 ? HistoryState::kReset : HistoryState::kRest, light).direct;
    const auto [truth, average] = errors(out, k + 1);
    if (k == 0) {
      EXPECT_GT(truth, 0.1f);  // blurred: the checkerboard's levels are 40% apart
    }
    if (k == frames - 1) {
      EXPECT_LT(truth, 0.03f);
      EXPECT_LT(average, 0.022f);
    }
  }
}

TEST(Denoiser, DirectPassesAtRestDropOnePerDoublingAfterTheFade) {
  EXPECT_EQ(direct_iterations_at_rest(3, 32, 0), 3);
  EXPECT_EQ(direct_iterations_at_rest(3, 32, 31), 3);
  EXPECT_EQ(direct_iterations_at_rest(3, 32, 32), 2);
  EXPECT_EQ(direct_iterations_at_rest(3, 32, 63), 2);
  EXPECT_EQ(direct_iterations_at_rest(3, 32, 64), 1);
  EXPECT_EQ(direct_iterations_at_rest(3, 32, 1 << 30), 1);  // never fewer than one
  EXPECT_EQ(direct_iterations_at_rest(5, 8, 40), 2);        // 8, 16, 32: three fewer
  EXPECT_EQ(direct_iterations_at_rest(3, 0, 1000), 3);      // 0: no fade
  EXPECT_EQ(direct_iterations_at_rest(0, 32, 1000), 0);
}

// A long rest thins the direct light's filter: the same frames give the same image as without
// the fade until rest_atrous_frames frames at rest, then a noisier one (fewer passes), which still
// beats the plain per-pixel average of the frames.
TEST(Denoiser, DirectFilterThinsOnlyAfterTheFadeFrames) {
  const int n = 24, fade = 8, frames = 2 * fade + 1;
  const GBuffer g = plane(n, n);
  Pcg32 rng(41);
  Denoiser faded, full;
  faded.settings().rest_atrous_frames = fade;
  full.settings().rest_atrous_frames = 0;
  Image sum(n, n, vec3(0.0f));
  for (int k = 0; k < frames; ++k) {
    const Image light = noisy(n, n, rng, 0.5f, [](int, int) { return 1.0f; });
    sum += light;
    const HistoryState state = k == 0 ? HistoryState::kReset : HistoryState::kRest;
    const Image a = run(faded, g, state, light).direct;
    const Image b = run(full, g, state, light).direct;
    if (k < fade) {
      EXPECT_EQ(a.pixels(), b.pixels()) << "frame " << k;
    } else if (k == frames - 1) {
      // 16 frames at rest: one pass fewer at 8 and at 16, one left of three.
      Image average = sum;
      average *= 1.0f / float(frames);
      const float da = deviation_x(a, 0, n, 0, n), db = deviation_x(b, 0, n, 0, n);
      EXPECT_GT(da, 1.5f * db);
      EXPECT_LT(da, 0.6f * deviation_x(average, 0, n, 0, n));
      EXPECT_NEAR(mean_x(a, 0, n, 0, n), mean_x(average, 0, n, 0, n), 0.01f);
    }
  }
}

// A long rest drops one indirect pass, once: until rest_indirect_frames frames at rest the image is
// the full filter's, from then on it is that of a filter with one pass fewer, however long the
// rest lasts.
TEST(Denoiser, IndirectFilterDropsOnePassAfterTheRestFrames) {
  const int n = 24, fade = 4, frames = 3 * fade;
  const GBuffer g = plane(n, n);
  Pcg32 rng(47);
  // (24 pixels high: indirect_iterations_for gives 4 passes for 8, 3 for 7.)
  Denoiser faded, full, fewer;
  faded.settings().rest_indirect_frames = fade;
  for (Denoiser* d : {&full, &fewer}) d->settings().rest_indirect_frames = 0;
  for (Denoiser* d : {&faded, &full}) d->settings().indirect_iterations = 8;
  fewer.settings().indirect_iterations = 7;
  const Image direct(n, n, vec3(1.0f));
  for (int k = 0; k < frames; ++k) {
    const Image light = noisy(n, n, rng, 0.5f, [](int x, int) { return x < 12 ? 1.0f : 2.0f; });
    const HistoryState state = k == 0 ? HistoryState::kReset : HistoryState::kRest;
    const Image a = run(faded, g, state, direct, &light).indirect;
    const Image b = run(full, g, state, direct, &light).indirect;
    const Image c = run(fewer, g, state, direct, &light).indirect;
    if (k < fade) {
      EXPECT_EQ(a.pixels(), b.pixels()) << "frame " << k;
    } else {
      EXPECT_EQ(a.pixels(), c.pixels()) << "frame " << k;
      EXPECT_NE(a.pixels(), b.pixels()) << "frame " << k;
    }
  }
}

// Rows are filtered independently: one thread or two give the same image, bit for bit.
TEST(Denoiser, ResultDoesNotDependOnTheThreadCount) {
  GBuffer g = World::seen_from(ivec2(0));
  for (size_t i = 0; i < g.size(); i += 5) g.mesh[i] = 2;  // object edges everywhere
  const GBuffer moved = World::seen_from(ivec2(1, 0));
  Pcg32 rng(31);
  const Image a = noisy(g.width, g.height, rng, 0.5f, [](int, int) { return 1.0f; });
  const Image b = noisy(g.width, g.height, rng, 0.5f, [](int, int) { return 2.0f; });
  std::vector<Image> results;
  for (const int threads : {1, 2}) {
    const ThreadLimit limit(threads);
    Denoiser d;
    run(d, g, HistoryState::kReset, a, &b);
    const Output out = run(d, moved, HistoryState::kWorldChanged, b, &a);
    results.push_back(out.direct + out.indirect);
  }
  EXPECT_EQ(results[0].pixels(), results[1].pixels());
}

TEST(Denoiser, ParametersHaveShortNamesAndBounds) {
  Denoiser d;
  std::set<std::string> names;
  for (const Param& p : d.params().all()) {
    names.insert(p.name);
    EXPECT_NE(p.name.rfind("denoise", 0), 0u) << p.name << ": no stage prefix, every name is short";
    EXPECT_FALSE(p.help.empty()) << p.name;
  }
  for (const char* name :
       {"temporal", "spatial", "atrous_iterations", "indirect_iterations", "indirect_resolution",
        "sigma_luminance", "sigma_normal", "sigma_depth", "history_max", "changing_history_max",
        "accumulated_history", "rest_atrous_frames", "clip_gamma", "modulation_alpha",
        "depth_tolerance", "normal_tolerance"})
    EXPECT_EQ(names.count(name), 1u) << name;
  d.params().set("atrous_iterations", "2");
  d.params().set("sigma_luminance", "8");
  d.params().set("spatial", "off");
  EXPECT_EQ(d.settings().atrous_iterations, 2);
  EXPECT_EQ(d.settings().sigma_luminance, 8.0f);
  EXPECT_FALSE(d.settings().spatial);
  EXPECT_THROW(d.params().set("history_max", "0"), Error);
  EXPECT_THROW(d.params().set("changing_history_max", "0"), Error);
  EXPECT_THROW(d.params().set("normal_tolerance", "2"), Error);
  EXPECT_THROW(d.params().set("modulation_alpha", "0"), Error);
}

TEST(Denoiser, DebugViewsShowHistoryMotionRawAndVariance) {
  GBuffer g = plane(8, 8);
  Pcg32 rng(29);
  const Image first = noisy(8, 8, rng, 0.5f, [](int, int) { return 1.0f; });
  Denoiser d;
  d.settings().history_max = 4;
  Image view;
  EXPECT_THROW(d.debug_view(DenoiseView::kRaw, view), Error);  // nothing kept yet
  run(d, g, HistoryState::kReset, first);
  EXPECT_THROW(d.debug_view(DenoiseView::kMotion, view), Error);  // not kept
  d.keep_raw(true);
  d.keep_motion(true);
  for (size_t i = 0; i < g.size(); ++i) g.motion[i] = vec2(i % 8 < 4 ? 0.0f : 1.0f, -2.0f);
  const Image second = noisy(8, 8, rng, 0.5f, [](int, int) { return 1.0f; });
  const Image indirect = noisy(8, 8, rng, 0.5f, [](int, int) { return 0.5f; });
  const Output out = run(d, g, HistoryState::kCameraMoved, second, &indirect);

  d.debug_view(DenoiseView::kRaw, view);
  for (size_t i = 0; i < g.size(); ++i)
    EXPECT_EQ(view.pixels()[i], second.pixels()[i] + indirect.pixels()[i]);
  d.debug_view(DenoiseView::kHistory, view);
  for (size_t i = 0; i < g.size(); ++i)
    EXPECT_EQ(view.pixels()[i], vec3(d.history_length()[i] / 4.0f));
  d.debug_view(DenoiseView::kMotion, view);
  EXPECT_EQ(view.at(1, 3), vec3(0.5f, 0.5f - 2.0f / 16.0f, 0.0f));
  EXPECT_EQ(view.at(5, 3), vec3(0.5f + 1.0f / 16.0f, 0.5f - 2.0f / 16.0f, 0.0f));
  d.debug_view(DenoiseView::kVariance, view);
  for (size_t i = 0; i < g.size(); ++i) EXPECT_GT(view.pixels()[i].x, 0.0f);
  d.debug_view(DenoiseView::kDenoised, view);
  for (size_t i = 0; i < g.size(); ++i)
    expect_near_rel(view.pixels()[i], out.direct.pixels()[i] + out.indirect.pixels()[i], 1e-5f,
                    "denoised view");

  // Without keep_raw the copies are gone; the motion is this run's while kept.
  d.keep_raw(false);
  for (vec2& m : g.motion) m = vec2(-4.0f, 8.0f);
  run(d, g, HistoryState::kCameraMoved, second, &indirect);
  EXPECT_THROW(d.debug_view(DenoiseView::kRaw, view), Error);
  EXPECT_THROW(d.debug_view(DenoiseView::kDenoised, view), Error);
  d.debug_view(DenoiseView::kMotion, view);
  EXPECT_EQ(view.at(2, 2), vec3(0.25f, 1.0f, 0.0f));
  d.keep_motion(false);
  run(d, g, HistoryState::kCameraMoved, second, &indirect);
  EXPECT_THROW(d.debug_view(DenoiseView::kMotion, view), Error);
}

TEST(Denoiser, RecordsItsSubStages) {
  const GBuffer g = plane(4, 4);
  for (int half_direct_frames : {0, 1}) {
    for (int indirect_resolution : {1, 2}) {
      Denoiser d;
      d.settings().half_direct_frames = half_direct_frames;
      d.settings().indirect_resolution = indirect_resolution;
      StageTimes times;
      Image direct(4, 4, vec3(1.0f)), indirect(4, 4, vec3(0.5f));
      d.run({g, HistoryState::kReset, IndirectHistory::kPerFrame, times}, direct, &indirect);
      std::set<std::string> names;
      for (const StageTime& s : times.stages()) names.insert(s.name);
      std::set<std::string> expected{"denoise/temporal", "denoise/variance", "denoise/atrous"};
      // (Both lights at half resolution are one stage, as both at full resolution are; indirect
      // light at full resolution is a stage of its own. When indirect light is filtered at half
      // resolution, last, its upsample remodulates.)
      if (half_direct_frames == 0 || indirect_resolution == 1) expected.insert("denoise/indirect");
      if (indirect_resolution == 1) expected.insert("denoise/remodulate");
      EXPECT_EQ(names, expected) << half_direct_frames << " " << indirect_resolution;
    }
  }
}

TEST(Denoiser, RefusesImagesOfAnotherSize) {
  const GBuffer g = plane(4, 4);
  Denoiser d;
  StageTimes times;
  Image direct(4, 3);
  EXPECT_THROW(d.run({g, HistoryState::kReset, IndirectHistory::kPerFrame, times}, direct, nullptr),
               Error);
}

}  // namespace
}  // namespace bounce
