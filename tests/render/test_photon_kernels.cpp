// The photon kernels against their launchers: the per-path and per-photon bodies a GPU backend
// runs (through the trace view, count-then-scan) give exactly what the CPU launchers give, and
// the CPU launchers give the same photons whatever the thread count.
#include <gtest/gtest.h>

#include <algorithm>

#include "bounce/core/parallel.h"
#include "bounce/core/parallel_primitives.h"
#include "bounce/render/photon_clearance.h"
#include "bounce/render/photon_tracing.h"
#include "bounce/scene/load.h"
#include "bounce/scene/scene_data.h"

namespace bounce {
namespace {

// The Cornell box (an area light) plus a sphere and a spot light: every kind of emitter, and a
// sphere light that photons can run into.
Scene lit_cornell() {
  Scene s = make_cornell();
  s.lights.push_back(Light::sphere(vec3(0.15f, 0.3f, 0.3f), 0.05f, vec3(20.0f)));
  s.lights.push_back(Light::spot(vec3(0.4f, 0.5f, 0.2f), vec3(0, -1, 0.2f), vec3(2.0f), 20, 35));
  s.finalize();
  return s;
}

void expect_same_photons(const PhotonBuffer& a, const PhotonBuffer& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.position[i], b.position[i]) << i;
    ASSERT_EQ(a.flux[i], b.flux[i]) << i;
    ASSERT_EQ(a.incident[i], b.incident[i]) << i;
    ASSERT_EQ(a.normal[i], b.normal[i]) << i;
  }
}

// The same photons, in the same order, up to the last bits of the hit distances: Embree's single
// rays (the trace view) and its streams (the CPU launcher) may round t differently.
void expect_matching_photons(const PhotonBuffer& a, const PhotonBuffer& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_LT(glm::length(a.position[i] - b.position[i]), 1e-5f) << i;
    ASSERT_LT(glm::length(a.flux[i] - b.flux[i]), 1e-5f * glm::length(a.flux[i])) << i;
    ASSERT_GT(glm::dot(a.incident_dir[i], b.incident_dir[i]), 0.9999f) << i;
    ASSERT_GT(glm::dot(a.normal_dir[i], b.normal_dir[i]), 0.9999f) << i;
  }
}

TEST(PhotonKernels, PerPathKernelWithCountThenScanGivesTheLaunchersPhotons) {
  const Scene scene = lit_cornell();
  const auto tracer = make_embree_tracer(scene);
  const SceneData data = SceneData::from(scene);
  for (int bounces : {-1, 3}) {
    PhotonTraceSettings settings;
    settings.paths = 3000;
    settings.max_bounces = bounces;
    settings.pass = 2;
    PhotonTracer launcher;
    PhotonBuffer expected;
    const PhotonTraceStats stats = launcher.trace(scene, data.view(), *tracer, settings, expected);
    ASSERT_GT(expected.size(), settings.paths);

    // As a GPU backend runs it: count per path, scan, write per path to the scanned slots.
    const PhotonEmitters emitters = PhotonEmitters::from(scene);
    const PhotonPass pass = photon_pass(settings);
    const SceneView view = data.view();
    const TraceView trace = tracer->view();
    std::vector<uint32_t> first(pass.paths), rays(pass.paths);
    parallel_for(pass.paths, [&](size_t i) {
      first[i] = trace_photon_path(
          view, trace, emitters.view(), pass, uint32_t(i), [](uint32_t, const PhotonDeposit&) {},
          rays[i]);
    });
    const uint32_t total = exclusive_scan(first);
    PhotonBuffer written;
    written.resize(total);
    const PhotonView out = written.view();
    parallel_for(pass.paths, [&](size_t i) {
      uint32_t traced;
      trace_photon_path(
          view, trace, emitters.view(), pass, uint32_t(i),
          [&](uint32_t k, const PhotonDeposit& d) { store_photon(out, first[i] + k, d); }, traced);
    });
    written.unpack_directions();
    expect_matching_photons(written, expected);
    uint64_t traced = 0;
    for (uint32_t r : rays) traced += r;
    EXPECT_EQ(traced, stats.rays);
  }
}

TEST(PhotonKernels, LauncherGivesTheSamePhotonsWithOneOrTwoThreads) {
  const Scene scene = lit_cornell();
  const auto tracer = make_embree_tracer(scene);
  PhotonTraceSettings settings;
  settings.paths = 5000;
  PhotonBuffer one, two;
  {
    ThreadLimit limit(1);
    PhotonTracer().trace(scene, *tracer, settings, one);
  }
  {
    ThreadLimit limit(2);
    PhotonTracer().trace(scene, *tracer, settings, two);
  }
  expect_same_photons(one, two);
}

TEST(PhotonKernels, PhotonsEndOnSphereLights) {
  // The Cornell box lit by a point light under its ceiling, then with a large sphere light below
  // the point light too: the photons that run into it end there.
  Scene box = make_cornell();
  box.lights.clear();
  box.meshes.erase(std::remove_if(box.meshes.begin(), box.meshes.end(),
                                  [&](const Mesh& m) { return m.name == "light"; }),
                   box.meshes.end());
  box.lights.push_back(Light::point(vec3(0.28f, 0.45f, 0.28f), vec3(1.0f)));
  Scene with_sphere = box;
  // Radiance low enough that (almost) no path starts on it: it is there to block.
  with_sphere.lights.push_back(Light::sphere(vec3(0.28f, 0.25f, 0.28f), 0.12f, vec3(1e-6f)));
  box.finalize();
  with_sphere.finalize();
  PhotonTraceSettings settings;
  settings.paths = 20000;
  settings.max_bounces = 1;
  const auto stored_flux = [&](const Scene& s, PhotonBuffer& photons) {
    const auto tracer = make_embree_tracer(s);
    PhotonTracer().trace(s, *tracer, settings, photons);
    float sum = 0.0f;
    for (const vec3& f : photons.flux) sum += f.x + f.y + f.z;
    return sum;
  };
  PhotonBuffer open_photons, blocked_photons;
  const float open = stored_flux(box, open_photons);
  const float blocked = stored_flux(with_sphere, blocked_photons);
  // The sphere subtends 10% of the light's directions (sin = 0.12 / 0.2), and more photons run into
  // it after their bounce; both runs draw the same paths, so the difference is not noise.
  EXPECT_LT(blocked, 0.92f * open) << blocked / open;
  EXPECT_GT(blocked, 0.6f * open);
  for (const vec3& p : blocked_photons.position)
    ASSERT_GT(glm::length(p - vec3(0.28f, 0.25f, 0.28f)), 0.12f);
}

TEST(PhotonKernels, PerPhotonClearanceKernelGivesTheLaunchersClearances) {
  const Scene scene = lit_cornell();
  const auto tracer = make_embree_tracer(scene);
  PhotonBuffer photons;
  PhotonTraceSettings settings;
  settings.paths = 2000;
  PhotonTracer().trace(scene, *tracer, settings, photons);
  const float radius = 0.1f;
  compute_photon_clearance(*tracer, radius, photons);
  PhotonBuffer copy = photons;
  std::fill(copy.clearance.begin(), copy.clearance.end(), -1.0f);
  std::fill(copy.min_clearance.begin(), copy.min_clearance.end(), -1.0f);
  const PhotonView view = copy.view();
  const TraceView trace = tracer->view();
  parallel_for(copy.size(), [&](size_t i) { photon_clearance(trace, view, i, radius); });
  // Equal up to the last bits of t (single rays and streams may round it differently).
  for (size_t k = 0; k < copy.clearance.size(); ++k)
    ASSERT_NEAR(copy.clearance[k], photons.clearance[k], 1e-6f) << k;
  for (size_t i = 0; i < copy.size(); ++i)
    ASSERT_NEAR(copy.min_clearance[i], photons.min_clearance[i], 1e-6f) << i;
  size_t blocked = 0;
  for (size_t i = 0; i < photons.size(); ++i) {
    const float* c = photons.clearance.data() + i * kClearanceRays;
    EXPECT_EQ(photons.min_clearance[i], *std::min_element(c, c + kClearanceRays));
    blocked += photons.min_clearance[i] < radius;
  }
  // Photons near the box's edges and the blocks see walls within the radius.
  EXPECT_GT(blocked, photons.size() / 10);
  EXPECT_LT(blocked, photons.size());
}

}  // namespace
}  // namespace bounce
