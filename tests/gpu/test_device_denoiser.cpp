// The denoiser on the GPU (gpu/device_denoiser.h) against the CPU's Denoiser on the same Cornell
// frames: a reset, frames at rest, a camera move and a world change, with and without indirect
// light. Skips without a CUDA GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bounce/core/rng.h"
#include "bounce/gpu/cuda_device.h"
#include "bounce/gpu/device_denoiser_check.h"
#include "bounce/render/denoiser.h"
#include "bounce/render/gbuffer.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"
#include "bounce/trace/tracer.h"

namespace bounce {
namespace {

// Odd sizes: the half-resolution indirect light has a clamped last column and row.
constexpr int kWidth = 49, kHeight = 37;

Camera moved_camera(const Camera& c) {
  Camera m = c;
  const vec3 side = glm::normalize(glm::cross(c.look_at - c.position, c.up));
  m.position += 0.03f * side + vec3(0.0f, 0.01f, 0.02f);
  m.look_at += 0.02f * side;
  return m;
}

// Noisy light shaped by the G-buffer: albedo times a smooth level times (1 +- 0.5 noise), plus
// the emission seen directly, so demodulation, the emitter and the edges all take part.
Image noisy_light(const GBuffer& g, Pcg32& rng, float level, bool emission) {
  Image out(g.width, g.height);
  for (size_t i = 0; i < g.size(); ++i) {
    const float noise = 1.0f + 0.5f * (2.0f * rng.next_float() - 1.0f);
    const float shape = level * (1.0f + 0.5f * std::sin(4.0f * g.position[i].x));
    out.data()[i] = g.hit(i) ? g.albedo[i] * (shape * noise) : vec3(0.0f);
    if (emission) out.data()[i] += g.emission[i];
  }
  return out;
}

struct Difference {
  double mean_abs = 0.0, max_abs = 0.0, mean = 0.0;
};
Difference difference(const Image& a, const Image& b) {
  Difference d;
  for (size_t i = 0; i < a.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double e = std::fabs(double(a.data()[i][c]) - double(b.data()[i][c]));
      d.mean_abs += e;
      d.max_abs = std::max(d.max_abs, e);
      d.mean += std::fabs(double(b.data()[i][c]));
    }
  const double count = 3.0 * double(a.pixel_count());
  d.mean_abs /= count;
  d.mean /= count;
  return d;
}

// Float reordering (fused multiply-adds, the GPU's exp2 against the CPU's cubic with 1e-4
// relative error in the filter weights) moves each weight by ~1e-4 relative; the filter's
// outputs are weighted means, so they move by about that much of the local light: mean
// differences stay far below 1e-3 of the mean light, single pixels (an edge tap whose weight
// sits at a threshold) within 2% of the brightest light. Unfiltered output differs from the
// filtered by ~10% of the mean (the noise is +-50%).
void expect_same(const Image& gpu, const Image& cpu, const Image& raw, const char* what,
                 int frame) {
  const Difference d = difference(gpu, cpu);
  double brightest = 0.0;
  for (size_t i = 0; i < cpu.pixel_count(); ++i)
    brightest = std::max(brightest, double(max_component(cpu.data()[i])));
  EXPECT_LT(d.mean_abs, 1e-3 * d.mean) << what << " frame " << frame;
  EXPECT_LT(d.max_abs, 2e-2 * brightest) << what << " frame " << frame;
  // The filter did something: the CPU's output is far from the raw input, so the bound above
  // would catch a device that returned it unfiltered.
  EXPECT_GT(difference(raw, cpu).mean_abs, 20.0 * d.mean_abs + 1e-3 * d.mean)
      << what << " frame " << frame;
}

void compare_sequence(bool with_indirect, IndirectHistory history, int indirect_resolution) {
  if (!cuda_device_info().available) GTEST_SKIP() << "no CUDA GPU: " << cuda_device_info().reason;
  const Scene scene = make_cornell();
  const auto tracer = make_embree_tracer(scene);
  const SceneData data = SceneData::from(scene);
  Denoiser cpu;
  cpu.settings().indirect_resolution = indirect_resolution;
  const DenoiseSettings settings = cpu.settings();
  DeviceDenoiserHost gpu;
  Pcg32 rng(3);
  const Camera cameras[2] = {scene.camera, moved_camera(scene.camera)};
  const HistoryState states[] = {HistoryState::kReset,        HistoryState::kRest,
                                 HistoryState::kRest,         HistoryState::kCameraMoved,
                                 HistoryState::kWorldChanged, HistoryState::kWorldChanged};
  // The last world change moved a spot light only: direct light's history is clipped in its
  // cone (the box's left half, seen from the camera), kept elsewhere.
  LightChangeRegion spot = LightChangeRegion::none();
  spot.cones = 1;
  spot.apex[0] = scene.camera.position;
  const vec3 forward = scene.camera.look_at - scene.camera.position;
  spot.axis[0] = glm::normalize(forward - 0.3f * glm::length(forward) * vec3(1.0f, 0.0f, 0.0f));
  spot.cos_outer[0] = std::cos(0.3f);
  CameraRays previous = CameraRays::from(cameras[0], kWidth, kHeight);
  for (int f = 0; f < int(std::size(states)); ++f) {
    const HistoryState state = states[f];
    const Camera& camera =
        cameras[state == HistoryState::kCameraMoved || state == HistoryState::kWorldChanged ? 1
                                                                                            : 0];
    const CameraRays rays = CameraRays::from(camera, kWidth, kHeight);
    GBuffer g;
    g.resize(kWidth, kHeight);
    build_gbuffer(data.view(), *tracer, rays, vec2(0.5f), g);
    compute_motion(data.view(), rays, previous, g);
    previous = rays;
    const Image raw_direct = noisy_light(g, rng, 1.0f, true);
    const Image raw_indirect = noisy_light(g, rng, 0.3f, false);
    Image cpu_direct = raw_direct, cpu_indirect = raw_indirect;
    Image gpu_direct = raw_direct, gpu_indirect = raw_indirect;
    StageTimes times;
    const LightChangeRegion region = f == 5 ? spot : LightChangeRegion::all();
    cpu.run({g, state, history, times, true, region}, cpu_direct,
            with_indirect ? &cpu_indirect : nullptr);
    gpu.run(settings, g, state, history, gpu_direct, with_indirect ? &gpu_indirect : nullptr,
            region);
    expect_same(gpu_direct, cpu_direct, raw_direct, "direct", f);
    if (with_indirect) expect_same(gpu_indirect, cpu_indirect, raw_indirect, "indirect", f);
  }
}

TEST(DeviceDenoiser, DirectLightMatchesTheCpu) {
  compare_sequence(false, IndirectHistory::kPerFrame, 2);
}

TEST(DeviceDenoiser, HalfResolutionIndirectLightMatchesTheCpu) {
  compare_sequence(true, IndirectHistory::kPerFrame, 2);
}

TEST(DeviceDenoiser, FullResolutionAccumulatedIndirectLightMatchesTheCpu) {
  compare_sequence(true, IndirectHistory::kAccumulated, 1);
}

TEST(DeviceDenoiser, IndirectLightFromARingMatchesTheCpu) {
  compare_sequence(true, IndirectHistory::kRing, 2);
}

}  // namespace
}  // namespace bounce
