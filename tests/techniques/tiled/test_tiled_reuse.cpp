// tiled keeps its photons while only the camera moves: the passes it holds, gathered from the
// new view, are exactly a fresh gather of the same photons; changes of the world restart them;
// without accumulation every frame has its own photons.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "bounce/core/parallel.h"
#include "bounce/metrics/image_metrics.h"
#include "bounce/render/photon_clearance.h"
#include "bounce/render/photon_gather.h"
#include "bounce/render/photon_tracing.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/tiled/photon_history.h"
#include "bounce/techniques/tiled/tiled.h"
#include "render/render_test_util.h"

namespace bounce {
namespace {

// One photon at x = `marker`, so that a pass can be recognised.
void fill_marker_pass(PhotonBuffer& b, float marker, bool clearance) {
  b.clear();
  b.position = {vec3(marker, 0.0f, 0.0f), vec3(marker, 1.0f, 0.0f)};
  b.flux = {vec3(marker), vec3(marker)};
  b.incident = {1u, 2u};
  b.normal = {3u, 4u};
  b.incident_dir = {vec3(0, -1, 0), vec3(0, -1, 0)};
  b.normal_dir = {vec3(0, 1, 0), vec3(0, 1, 0)};
  if (clearance) {
    b.clearance.assign(2 * kClearanceRays, marker);
    b.min_clearance = {marker, marker};
  }
}

TEST(PhotonHistory, KeepsTheNewestPassesOldestFirst) {
  PhotonHistory history;
  history.reset(3);
  for (uint32_t sample = 10; sample < 15; ++sample)
    fill_marker_pass(history.add(sample), float(sample), true);
  ASSERT_EQ(history.size(), 3u);
  EXPECT_EQ(history.photon_count(), 6u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(history.sample(k), 12u + k);
    EXPECT_EQ(history.pass(k).position[0].x, float(12 + k));
  }
  EXPECT_EQ(history.newest().position[0].x, 14.0f);

  PhotonBuffer all;
  history.concatenate(all);
  ASSERT_EQ(all.size(), 6u);
  ASSERT_EQ(all.clearance.size(), 6u * kClearanceRays);
  for (size_t i = 0; i < 6; ++i) {
    const float marker = float(12 + i / 2);
    EXPECT_EQ(all.position[i], vec3(marker, float(i % 2), 0.0f)) << i;
    EXPECT_EQ(all.flux[i], vec3(marker)) << i;
    EXPECT_EQ(all.incident[i], 1u + i % 2) << i;
    EXPECT_EQ(all.normal_dir[i], vec3(0, 1, 0)) << i;
    EXPECT_EQ(all.min_clearance[i], marker) << i;
    EXPECT_EQ(all.clearance[i * kClearanceRays + kClearanceRays - 1], marker) << i;
  }

  // A pass without clearances: the union has none.
  fill_marker_pass(history.add(15), 15.0f, false);
  history.concatenate(all);
  EXPECT_EQ(all.size(), 6u);
  EXPECT_TRUE(all.clearance.empty());
  EXPECT_TRUE(all.min_clearance.empty());

  history.reset(2);
  EXPECT_EQ(history.size(), 0u);
  EXPECT_EQ(history.capacity(), 2u);
}

constexpr int kSize = 40;

Camera moved_camera(const Camera& a) {
  Camera b = a;
  b.position += vec3(0.06f, -0.04f, 0.10f);
  b.look_at += vec3(-0.05f, 0.03f, 0.0f);
  return b;
}

FrameSettings still_frames(bool accumulate = true) {
  FrameSettings s;
  s.width = s.height = kSize;
  s.light_samples = 1;
  s.accumulate = accumulate;
  return s;
}

struct TiledRun {
  const Scene scene = make_cornell();
  std::unique_ptr<Tracer> tracer = make_embree_tracer(scene);
  TiledPhotonMapping* tiled = nullptr;
  std::unique_ptr<Renderer> renderer;

  explicit TiledRun(int history_passes) {
    auto technique = std::make_unique<TiledPhotonMapping>();
    tiled = technique.get();
    tiled->settings().photons = 600;
    // Every pixel gathered, after a move too: comparable with a brute-force gather.
    tiled->settings().lowres = 1;
    tiled->settings().motion_lowres = 1;
    tiled->settings().history_passes = history_passes;
    // One pass per frame, also right after a restart (the boost has its own tests below).
    tiled->settings().restart_passes = 1;
    renderer = std::make_unique<Renderer>(scene, *tracer, std::move(technique));
  }
  const Frame& render(const Camera& camera, bool accumulate = true) {
    return renderer->render(camera, still_frames(accumulate));
  }
};

// Pass `sample` of the run's photons (its 600 paths) traced afresh outside the technique, with
// clearances out to `full_radius`.
PhotonBuffer traced_pass(const TiledRun& run, uint32_t sample, float full_radius) {
  PhotonTraceSettings ts;
  ts.paths = 600;
  ts.pass = sample;
  PhotonBuffer pass;
  PhotonTracer().trace(run.scene, *run.tracer, ts, pass);
  compute_photon_clearance(*run.tracer, full_radius, pass);
  return pass;
}

void append_pass(PhotonBuffer& all, const PhotonBuffer& pass) {
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  append(all.position, pass.position);
  append(all.flux, pass.flux);
  append(all.incident, pass.incident);
  append(all.normal, pass.normal);
  append(all.incident_dir, pass.incident_dir);
  append(all.normal_dir, pass.normal_dir);
  append(all.clearance, pass.clearance);
  append(all.min_clearance, pass.min_clearance);
}

// The indirect radiance of every pixel of `g` from `photons`, summed photon by photon over all of
// them (no tiles) at `radius`, divided by `passes`.
Image brute_force_gather(const GBuffer& g, const PhotonBuffer& photons, float radius,
                         uint32_t passes) {
  Image out(g.width, g.height);
  const GatherSettings gs{radius, 0.1f * radius, true};
  for (size_t i = 0; i < g.size(); ++i) {
    if (!g.hit(i)) continue;
    vec3 sum(0.0f);
    for (size_t k = 0; k < photons.size(); ++k) {
      const float w = gather_weight(photons.view(), k, g.position[i], g.normal[i], gs);
      if (w > 0.0f) sum += photons.flux[k] * w;
    }
    out.pixels()[i] = cone_filter_radiance(sum, g.albedo[i], radius) * (1.0f / float(passes));
  }
  return out;
}

// Frames that gather the kept passes after a camera move leave edge pixels to the denoiser's
// filter (motion_edges off), where each edge gather would read every kept pass; frames at rest
// re-estimate them, and motion_edges brings them back in motion.
TEST(TiledReuse, CameraMovesReestimateNoEdgesUnlessAsked) {
  for (const bool motion_edges : {false, true}) {
    TiledRun run(4);
    run.tiled->settings().lowres = 4;
    run.tiled->settings().motion_lowres = 4;
    run.tiled->settings().motion_edges = motion_edges;
    const Camera a = run.scene.camera, b = moved_camera(a);
    for (int k = 0; k < 3; ++k) run.render(a);
    const size_t at_rest = run.tiled->edge_pixels();
    ASSERT_TRUE(run.render(b).change.camera_only());
    const size_t moved = run.tiled->edge_pixels();
    // In a 40-pixel image of 4x4 blocks most blocks hold an edge of the box or its walls.
    EXPECT_GT(at_rest, size_t(kSize * kSize / 20));
    if (motion_edges)
      EXPECT_GT(moved, size_t(kSize * kSize / 20));
    else
      EXPECT_LT(moved, at_rest / 4);  // only blocks whose sample misses the scene, if any
  }
}

TEST(TiledReuse, CameraMoveGathersTheHeldPassesFreshFromTheNewView) {
  constexpr int kHistory = 4;
  TiledRun run(kHistory);
  const Camera a = run.scene.camera, b = moved_camera(a);
  for (int k = 0; k < 6; ++k) run.render(a);  // frames 0..5 at rest
  ASSERT_EQ(run.tiled->passes(), 6u);
  const Frame& f = run.render(b);  // frame 6: only the camera moved
  ASSERT_TRUE(f.change.camera_only());

  // The four newest passes are held (frames 3..6) and gathered together at the radius whose disc
  // is the mean of the discs of four progressive passes.
  const TiledPhotonMapping& tiled = *run.tiled;
  ASSERT_EQ(tiled.passes(), uint32_t(kHistory));
  ASSERT_EQ(tiled.history().size(), size_t(kHistory));
  const float alpha = tiled.settings().alpha;
  const float full = 0.03f * run.scene.bounds.diagonal();
  const float area1 = 1.0f, area2 = alpha, area3 = area2 * (1 + alpha) / 2,
              area4 = area3 * (2 + alpha) / 3;
  const float r_union = full * std::sqrt((area1 + area2 + area3 + area4) / 4);
  EXPECT_NEAR(tiled.last_radius(), r_union, 1e-6f * full);

  // The same passes traced afresh, outside the technique, and gathered by brute force from B.
  PhotonBuffer all;
  for (uint32_t frame = 3; frame <= 6; ++frame) {
    EXPECT_EQ(tiled.history().sample(frame - 3), frame);
    const PhotonBuffer pass = traced_pass(run, frame, full);
    ASSERT_EQ(pass.position, tiled.history().pass(frame - 3).position);
    append_pass(all, pass);
  }
  const Image fresh = brute_force_gather(f.gbuffer, all, r_union, kHistory);
  size_t lit = 0;
  for (size_t i = 0; i < fresh.pixel_count(); ++i) {
    const vec3 expected = fresh.pixels()[i], got = f.indirect.pixels()[i];
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(got[c], expected[c], 1e-5f * expected[c] + 1e-7f) << "pixel " << i;
    lit += expected.x > 0.0f ? 1 : 0;
  }
  EXPECT_GT(lit, fresh.pixel_count() / 2);  // the comparison covers real gathers

  // At rest again the next pass joins the four, at the radius of the fifth progressive pass.
  run.render(b);
  EXPECT_EQ(tiled.passes(), uint32_t(kHistory + 1));
  const float r5 = full * std::sqrt(area4 * (3 + alpha) / 4);
  EXPECT_NEAR(tiled.last_radius(), r5, 1e-6f * full);
}

// Passes first..last of the progressive sequence gathered together: the radius whose disc is the
// mean of theirs.
float mean_disc_radius(float full, float alpha, uint32_t first, uint32_t last) {
  float area = 1.0f, sum = 0.0f;
  for (uint32_t i = 1; i <= last; ++i) {
    if (i >= first) sum += area;
    area *= (float(i - 1) + alpha) / float(i);
  }
  return full * std::sqrt(sum / float(last - first + 1));
}

TEST(TiledReuse, FramesAfterARestartTraceExtraPassesGatheredTogether) {
  TiledRun run(8);
  run.tiled->settings().restart_passes = 3;
  run.tiled->settings().restart_frames = 2;
  const Camera a = run.scene.camera;
  const float full = 0.03f * run.scene.bounds.diagonal(), alpha = run.tiled->settings().alpha;

  // The first frame counts as after a long still period: frames 0 and 1 trace three passes each,
  // then one per frame.
  const Frame& f0 = run.render(a);
  EXPECT_EQ(run.tiled->frame_passes(), 3u);
  EXPECT_EQ(run.tiled->passes(), 3u);
  ASSERT_EQ(run.tiled->history().size(), 3u);
  EXPECT_NEAR(run.tiled->last_radius(), mean_disc_radius(full, alpha, 1, 3), 1e-6f * full);

  // Frame 0's image is the three passes (samples 0, 2^28, 2^29) traced afresh and gathered by
  // brute force together at that radius: the sum of their flux over three passes.
  PhotonBuffer all;
  for (uint32_t k = 0; k < 3; ++k) {
    EXPECT_EQ(run.tiled->history().sample(k), k * 0x10000000u);
    const PhotonBuffer pass = traced_pass(run, k * 0x10000000u, full);
    ASSERT_EQ(pass.position, run.tiled->history().pass(k).position);
    append_pass(all, pass);
  }
  const Image fresh = brute_force_gather(f0.gbuffer, all, mean_disc_radius(full, alpha, 1, 3), 3);
  size_t lit = 0;
  for (size_t i = 0; i < fresh.pixel_count(); ++i) {
    const vec3 expected = fresh.pixels()[i], got = f0.indirect.pixels()[i];
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(got[c], expected[c], 1e-5f * expected[c] + 1e-7f) << "pixel " << i;
    lit += expected.x > 0.0f ? 1 : 0;
  }
  EXPECT_GT(lit, fresh.pixel_count() / 2);

  run.render(a);  // frame 1: passes 4..6 at their mean disc
  EXPECT_EQ(run.tiled->frame_passes(), 3u);
  EXPECT_EQ(run.tiled->passes(), 6u);
  EXPECT_NEAR(run.tiled->last_radius(), mean_disc_radius(full, alpha, 4, 6), 1e-6f * full);
  run.render(a);  // frame 2: one pass, the seventh progressive one
  EXPECT_EQ(run.tiled->frame_passes(), 1u);
  EXPECT_EQ(run.tiled->passes(), 7u);
  EXPECT_NEAR(run.tiled->last_radius(), mean_disc_radius(full, alpha, 7, 7), 1e-6f * full);

  // A light change after the still period is boosted again...
  SceneChange light;
  light.lights = true;
  run.renderer->scene_changed(light);
  run.render(a);
  EXPECT_EQ(run.tiled->frame_passes(), 3u);
  EXPECT_EQ(run.tiled->passes(), 3u);
  // ...but under continuous change (a restart every frame) no frame is, so an animation's frame
  // time stays flat.
  for (int k = 0; k < 4; ++k) {
    run.renderer->scene_changed(light);
    run.render(a);
    EXPECT_EQ(run.tiled->frame_passes(), 1u) << k;
    EXPECT_EQ(run.tiled->passes(), 1u) << k;
  }
  // Nor without accumulation, where every frame stands alone.
  for (int k = 0; k < 6; ++k) run.render(a, false);
  EXPECT_EQ(run.tiled->frame_passes(), 1u);
  EXPECT_EQ(run.tiled->passes(), 1u);
}

TEST(TiledReuse, ChangesOfTheWorldRestartTheCameraDoesNot) {
  TiledRun run(8);
  const Camera a = run.scene.camera, b = moved_camera(a);
  const float full = 0.03f * run.scene.bounds.diagonal();
  for (int k = 0; k < 5; ++k) run.render(a);
  ASSERT_EQ(run.tiled->passes(), 5u);
  ASSERT_LT(run.tiled->last_radius(), 0.9f * full);

  // A camera move keeps the five passes and adds the sixth.
  run.render(b);
  EXPECT_EQ(run.tiled->passes(), 6u);
  EXPECT_EQ(run.tiled->history().size(), 6u);
  EXPECT_LT(run.tiled->last_radius(), 0.9f * full);

  const auto expect_restart = [&](const char* what) {
    EXPECT_EQ(run.tiled->passes(), 1u) << what;
    EXPECT_EQ(run.tiled->history().size(), 1u) << what;
    EXPECT_NEAR(run.tiled->last_radius(), full, 1e-6f * full) << what;
  };
  SceneChange light;
  light.lights = true;
  run.renderer->scene_changed(light);
  run.render(b);
  expect_restart("light");
  run.render(b);
  EXPECT_EQ(run.tiled->passes(), 2u);

  SceneChange material;
  material.materials = true;
  run.renderer->scene_changed(material);
  run.render(b);
  expect_restart("material");

  SceneChange mesh;
  mesh.moved_meshes = {0};
  run.renderer->scene_changed(mesh);
  run.render(b);
  expect_restart("moved mesh");

  run.tiled->params().set("slab", "0.2");
  run.render(b);
  expect_restart("parameter");
}

// The indirect image of the frame after a camera move, at the defaults (the kept passes gathered
// at motion_lowres through the hash grid).
Image indirect_after_move(int threads) {
  const ThreadLimit limit(threads);
  const Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, std::make_unique<TiledPhotonMapping>());
  for (int k = 0; k < 5; ++k) renderer.render(scene.camera, still_frames());
  return renderer.render(moved_camera(scene.camera), still_frames()).indirect;
}

TEST(TiledReuse, FramesAfterAMoveAreIdenticalWithOneAndTwoThreads) {
  const Image one = indirect_after_move(1);
  const Image two = indirect_after_move(2);
  for (size_t i = 0; i < one.pixel_count(); ++i)
    ASSERT_EQ(one.pixels()[i], two.pixels()[i]) << "pixel " << i;
  EXPECT_GT(mean(one).x, 0.0f);
}

TEST(TiledReuse, WithoutAccumulationEachFrameHasItsOwnPhotons) {
  EXPECT_EQ(TiledPhotonMapping().photons().size(), 0u);  // none before the first frame
  TiledRun run(8);
  const Camera a = run.scene.camera;
  std::vector<vec3> first_photons;
  std::vector<Image> images;
  for (int k = 0; k < 3; ++k) {
    const Frame& f = run.render(a, false);
    EXPECT_EQ(run.tiled->passes(), 1u);
    EXPECT_EQ(run.tiled->history().size(), 1u);
    first_photons.push_back(run.tiled->photons().position.at(0));
    images.push_back(f.indirect);
  }
  EXPECT_NE(first_photons[0], first_photons[1]);
  EXPECT_NE(first_photons[1], first_photons[2]);
  const double diff = compare_images(images[0], images[1]).linear.mse;
  EXPECT_GT(diff, 0.0);
}

}  // namespace
}  // namespace bounce
