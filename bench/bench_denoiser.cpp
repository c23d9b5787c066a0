// Denoiser: milliseconds per run at 512x512 on synthetic frames (a room of five walls and a
// block in front, textured albedo, smooth light with per-pixel noise, the camera moving sideways
// at about 0.3 m/s at 30 frames per second, with exact motion vectors), direct and indirect light,
// by a-trous iterations and history state (kCameraMoved in steady state, kReset, where every
// pixel's variance is estimated spatially, and kRest), on one or two threads. Counters: each
// sub-stage's time, and the relative RMS error of the input and of the output against the
// noise-free light. The process CPU time counts TBB's waiting workers too.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/core/rng.h"
#include "bounce/render/denoiser.h"

namespace {

using namespace bounce;

constexpr int kSize = 512;

struct Plane {
  vec3 normal;   // facing the room's inside
  float offset;  // dot(normal, p) = offset on the plane
  uint32_t mesh;
};
constexpr Plane kPlanes[] = {{vec3(0, 1, 0), -1.0f, 0},  {vec3(0, -1, 0), -1.5f, 1},
                             {vec3(1, 0, 0), -1.5f, 2},  {vec3(-1, 0, 0), -1.5f, 3},
                             {vec3(0, 0, -1), -4.0f, 4}, {vec3(0, 0, -1), -2.5f, 5}};
const vec3 kLight(0.3f, 1.2f, 2.0f);
const float kTanHalf = std::tan(0.5f * 60.0f * kPi / 180.0f);  // 60 degrees vertical field

// The camera looks along +z from a point swinging along x: 0.25 m amplitude, 150 frames a period.
vec3 camera_at(int frame) {
  return vec3(0.25f * std::sin(2.0f * kPi * float(frame) / 150.0f), 0.0f, 0.0f);
}

// Where point q (world) lands on the image of a camera at c: pixel coordinates, centres at +0.5.
vec2 project(vec3 q, vec3 c) {
  const vec3 p = q - c;
  return vec2((p.x / (p.z * kTanHalf) + 1.0f) * 0.5f * kSize,
              (1.0f - p.y / (p.z * kTanHalf)) * 0.5f * kSize);
}

// One frame: its G-buffer, noise-free light, and the light with noise.
struct Frame {
  GBuffer g;
  Image clean_direct, clean_indirect, direct, indirect;

  void render(int frame, Pcg32& rng) {
    if (g.width != kSize) {
      g.resize(kSize, kSize);
      for (Image* image : {&clean_direct, &clean_indirect, &direct, &indirect})
        *image = Image(kSize, kSize);
    }
    const vec3 eye = camera_at(frame), last_eye = camera_at(frame - 1);
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const size_t i = g.view().index(x, y);
        const vec3 d =
            glm::normalize(vec3((2.0f * (float(x) + 0.5f) / kSize - 1.0f) * kTanHalf,
                                (1.0f - 2.0f * (float(y) + 0.5f) / kSize) * kTanHalf, 1.0f));
        float best = 1e30f;
        const Plane* hit = &kPlanes[0];
        for (const Plane& p : kPlanes) {
          const float t = (p.offset - glm::dot(p.normal, eye)) / glm::dot(p.normal, d);
          const vec3 q = eye + t * d;
          // The block is a quad x in [-0.6, 0.3], y in [-1, 0.1] at z = 2.5.
          if (p.mesh == 5 && (q.x < -0.6f || q.x > 0.3f || q.y > 0.1f)) continue;
          if (t > 0.0f && t < best) {
            best = t;
            hit = &p;
          }
        }
        const vec3 q = eye + best * d;
        g.position[i] = q;
        g.normal[i] = g.geometric_normal[i] = hit->normal;
        const int checker =
            int(std::floor(4.0f * q.x) + std::floor(4.0f * q.y) + std::floor(4.0f * q.z));
        g.albedo[i] = checker % 2 ? vec3(0.7f, 0.6f, 0.5f) : vec3(0.3f, 0.5f, 0.2f);
        g.roughness[i] = 1.0f;
        g.f0[i] = vec3(0.04f);
        g.emission[i] = vec3(0.0f);
        g.depth[i] = q.z - eye.z;
        g.primitive[i] = hit->mesh * 2;
        g.mesh[i] = hit->mesh;
        g.barycentric[i] = vec2(0.0f);
        g.motion[i] = vec2(float(x) + 0.5f, float(y) + 0.5f) - project(q, last_eye);
        const vec3 to_light = kLight - q;
        const float irradiance = std::max(glm::dot(hit->normal, glm::normalize(to_light)), 0.0f) /
                                 glm::dot(to_light, to_light);
        const vec3 clean_d = g.albedo[i] * vec3(3.0f * irradiance);
        const vec3 clean_i = g.albedo[i] * vec3(0.2f + 0.05f * q.y);
        clean_direct.at(x, y) = clean_d;
        clean_indirect.at(x, y) = clean_i;
        // Unbiased noise: soft-shadow-like on direct light, photon-like on indirect light.
        direct.at(x, y) = clean_d * (0.5f + rng.next_float());
        const float u = rng.next_float(), v = rng.next_float(), w = rng.next_float();
        indirect.at(x, y) = clean_i * ((2.0f * u * v + 0.5f * w) / 0.75f);
      }
    }
  }
};

double relative_rms(const Image& out, const Image& clean) {
  double error = 0.0, energy = 0.0;
  for (size_t i = 0; i < out.pixel_count(); ++i) {
    const vec3 e = out.pixels()[i] - clean.pixels()[i];
    error += double(glm::dot(e, e));
    energy += double(glm::dot(clean.pixels()[i], clean.pixels()[i]));
  }
  return std::sqrt(error / energy);
}

// Args: a-trous iterations, history state (1: kCameraMoved in steady state, 0: kReset, 2: kRest;
// the errors mean nothing at rest, where the frames still move; 3: kWorldChanged, the camera
// moving and the world said to change, so the history is clipped to each frame's neighbourhood,
// as with a flashlight carried through a level), worker threads, 1 with indirect light or 0 for
// direct light alone, and the resolution divisor indirect light is filtered at. The iterations
// count for direct and indirect light alike.
void BM_Denoiser(benchmark::State& state) {
  const int iterations = int(state.range(0));
  const HistoryState measured = state.range(1) == 0   ? HistoryState::kReset
                                : state.range(1) == 1 ? HistoryState::kCameraMoved
                                : state.range(1) == 3 ? HistoryState::kWorldChanged
                                                      : HistoryState::kRest;
  ThreadLimit limit(int(state.range(2)));
  const bool with_indirect = state.range(3) != 0;
  Denoiser denoiser;
  denoiser.settings().atrous_iterations = iterations;
  denoiser.settings().indirect_iterations = iterations;
  denoiser.settings().indirect_resolution = int(state.range(4));
  denoiser.settings().spatial = iterations > 0;
  Frame f;
  Pcg32 rng(42);
  StageTimes times, total;
  int frame = 0;
  auto run = [&](HistoryState history) {
    times.clear();
    denoiser.run({f.g, history, IndirectHistory::kPerFrame, times}, f.direct,
                 with_indirect ? &f.indirect : nullptr);
  };
  // A history to reproject: 32 frames of camera motion.
  for (; frame < 32; ++frame) {
    f.render(frame, rng);
    run(frame == 0 ? HistoryState::kReset : HistoryState::kCameraMoved);
  }
  double raw_d = 0.0, raw_i = 0.0, out_d = 0.0, out_i = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    f.render(frame++, rng);
    raw_d += relative_rms(f.direct, f.clean_direct);
    raw_i += relative_rms(f.indirect, f.clean_indirect);
    state.ResumeTiming();
    run(measured);
    state.PauseTiming();
    for (const StageTime& s : times.stages()) total.add(s.name, s.ms);
    out_d += relative_rms(f.direct, f.clean_direct);
    out_i += relative_rms(f.indirect, f.clean_indirect);
    state.ResumeTiming();
  }
  const double runs = double(state.iterations());
  state.counters["temporal_ms"] = total.get("denoise/temporal") / runs;
  state.counters["variance_ms"] = total.get("denoise/variance") / runs;
  state.counters["atrous_ms"] = total.get("denoise/atrous") / runs;
  state.counters["indirect_ms"] = total.get("denoise/indirect") / runs;
  state.counters["remodulate_ms"] = total.get("denoise/remodulate") / runs;
  state.counters["raw_direct_err"] = raw_d / runs;
  state.counters["direct_err"] = out_d / runs;
  state.counters["raw_indirect_err"] = raw_i / runs;
  state.counters["indirect_err"] = out_i / runs;
  state.SetItemsProcessed(state.iterations() * int64_t(kSize) * kSize);
}

BENCHMARK(BM_Denoiser)
    ->ArgNames({"iterations", "history", "threads", "indirect", "resolution"})
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {1}, {2}, {1}, {1, 2}})
    ->Args({5, 0, 2, 1, 2})
    ->Args({5, 2, 2, 1, 2})
    ->Args({2, 1, 2, 0, 2})
    ->Args({4, 1, 2, 0, 2})
    ->Args({5, 1, 1, 1, 2})
    ->Args({5, 3, 1, 1, 2})
    ->Args({0, 1, 1, 1, 2})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
