// The technique contract: the Renderer's one notion of what changed, the prepare stage, the
// pipeline's accumulation setting and the G-buffer's triangle ids and barycentrics.
#include <gtest/gtest.h>

#include "bounce/render/renderer.h"
#include "bounce/scene/load.h"
#include "bounce/techniques/registry.h"

namespace bounce {
namespace {

// Records what the Renderer hands it, frame by frame.
class RecordingTechnique final : public Technique {
 public:
  explicit RecordingTechnique(std::vector<SceneChange>* prepared, std::vector<bool>* continued)
      : prepared_(prepared), continued_(continued) {
    params_.add_float("knob", &knob_, 0.0, 10.0, "a parameter to turn");
  }
  std::string name() const override { return "recording"; }
  void prepare(const PrepareContext& c) override {
    prepared_->push_back(c.change);
    c.times.add("prepare/recorded", 0.0);
  }
  void indirect(const FrameContext& c, Image& out) override {
    continued_->push_back(c.continue_accumulation());
    for (vec3& p : out.pixels()) p = vec3(float(continued_->size()));  // differs every frame
  }

 private:
  std::vector<SceneChange>* prepared_;
  std::vector<bool>* continued_;
  float knob_ = 1.0f;
};

FrameSettings tiny() {
  FrameSettings s;
  s.width = s.height = 8;
  s.light_samples = 1;
  s.accumulate = true;
  return s;
}

TEST(FrameContract, TheRendererTellsTheTechniqueWhatChanged) {
  Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  std::vector<SceneChange> seen;
  std::vector<bool> continued;
  Renderer renderer(scene, *tracer, std::make_unique<RecordingTechnique>(&seen, &continued));
  FrameSettings s = tiny();
  Camera moved = scene.camera;
  moved.position.x += 0.01f;

  renderer.render(scene.camera, s);  // 0: first frame, everything is new
  renderer.render(scene.camera, s);  // 1: nothing
  renderer.render(moved, s);         // 2: camera
  renderer.technique().params().set("knob", "2");
  renderer.render(moved, s);  // 3: parameters
  renderer.scene_changed(SceneChange{{}, true});
  renderer.render(moved, s);  // 4: lights
  s.light_samples = 2;
  renderer.render(moved, s);  // 5: frame settings count as parameters
  s.width = 16;
  renderer.render(moved, s);  // 6: a new size is a new camera
  renderer.render(moved, s);  // 7: nothing

  ASSERT_EQ(seen.size(), 8u);
  EXPECT_TRUE(seen[0].everything);
  EXPECT_FALSE(seen[1].any());
  EXPECT_TRUE(seen[2].camera_only());
  EXPECT_TRUE(seen[3].parameters && !seen[3].camera);
  EXPECT_TRUE(seen[4].lights && !seen[4].parameters && !seen[4].camera);
  EXPECT_TRUE(seen[5].parameters && !seen[5].lights);
  EXPECT_TRUE(seen[6].camera_only());
  EXPECT_FALSE(seen[7].any());
  const std::vector<bool> expected{false, true, false, false, false, false, false, true};
  EXPECT_EQ(continued, expected);
  EXPECT_FALSE(renderer.next_change(moved, s).any());
  s.width = 8;
  EXPECT_TRUE(renderer.next_change(moved, s).camera);
  EXPECT_FALSE(renderer.next_change(moved, s, true).any());  // a viewer's rescaling is not motion
}

TEST(FrameContract, PrepareIsATimedStageBeforeTheGBuffer) {
  const Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  std::vector<SceneChange> seen;
  std::vector<bool> continued;
  Renderer renderer(scene, *tracer, std::make_unique<RecordingTechnique>(&seen, &continued));
  const Frame& f = renderer.render(scene.camera, tiny());
  std::vector<std::string> names;
  for (const auto& stage : f.times.stages()) names.push_back(stage.name);
  const auto at = [&](const std::string& n) { return std::find(names.begin(), names.end(), n); };
  ASSERT_NE(at("prepare"), names.end());
  ASSERT_NE(at("prepare/recorded"), names.end());
  EXPECT_LT(at("prepare"), at("gbuffer"));
  EXPECT_LT(at("gbuffer"), at("indirect"));
}

TEST(FrameContract, PerFrameIndirectLightIsAveragedAtRestAndOnlyThen) {
  const Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  std::vector<SceneChange> seen;
  std::vector<bool> continued;
  Renderer renderer(scene, *tracer, std::make_unique<RecordingTechnique>(&seen, &continued));
  FrameSettings s = tiny();
  // The technique writes 1, 2, 3, ...: at rest the pipeline shows their running mean.
  EXPECT_EQ(renderer.render(scene.camera, s).indirect.at(0, 0), vec3(1.0f));
  EXPECT_EQ(renderer.render(scene.camera, s).indirect.at(0, 0), vec3(1.5f));
  const Frame& third = renderer.render(scene.camera, s);
  EXPECT_EQ(third.indirect.at(0, 0), vec3(2.0f));
  EXPECT_EQ(third.frames_averaged, 3);
  s.accumulate = false;
  const Frame& off = renderer.render(scene.camera, s);
  EXPECT_EQ(off.indirect.at(0, 0), vec3(4.0f));
  EXPECT_EQ(off.frames_averaged, 1);
}

// path's frame k at rest averages samples 0..k-1 itself: four one-sample frames must show what
// one four-sample frame shows. Averaged again by the pipeline they would not.
TEST(FrameContract, AccumulatingTechniquesAreNotAveragedTwice) {
  const Scene scene = make_cornell();
  EXPECT_EQ(make_technique("tiled")->indirect_history(), IndirectHistory::kAccumulated);
  const auto indirect = [&](int samples, int frames) {
    auto technique = make_technique("path");
    EXPECT_EQ(technique->indirect_history(), IndirectHistory::kAccumulated);
    technique->params().set("samples", std::to_string(samples));
    auto tracer = make_embree_tracer(scene);
    Renderer renderer(scene, *tracer, std::move(technique));
    Image last;
    for (int k = 0; k < frames; ++k) last = renderer.render(scene.camera, tiny()).indirect;
    return last;
  };
  const Image four_frames = indirect(1, 4), one_frame = indirect(4, 1);
  float total = 0.0f;
  for (size_t i = 0; i < one_frame.pixel_count(); ++i) {
    total += one_frame.pixels()[i].x + one_frame.pixels()[i].y + one_frame.pixels()[i].z;
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(four_frames.pixels()[i][c], one_frame.pixels()[i][c],
                  1e-5f * (1.0f + one_frame.pixels()[i][c]))
          << i;
  }
  EXPECT_GT(total, 0.0f);
}

TEST(FrameContract, GBufferHoldsTheTriangleItsBarycentricsAndTheMesh) {
  const Scene scene = make_cornell();
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique("direct"));
  FrameSettings s = tiny();
  s.width = s.height = 24;
  const GBuffer& g = renderer.render(scene.camera, s).gbuffer;
  size_t hits = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (!g.hit(i)) {
      EXPECT_EQ(g.mesh[i], kNoPrimitive);
      continue;
    }
    ++hits;
    ASSERT_LT(g.mesh[i], scene.meshes.size());
    const Mesh& mesh = scene.meshes[g.mesh[i]];
    const uint32_t triangle = g.primitive[i] - scene.triangle_offsets[g.mesh[i]];
    ASSERT_LT(triangle, mesh.triangles.size());
    const vec2 b = g.barycentric[i];
    EXPECT_GE(b.x, -1e-5f);
    EXPECT_GE(b.y, -1e-5f);
    EXPECT_LE(b.x + b.y, 1.0f + 1e-5f);
    // The barycentrics rebuild the hit point from the triangle's vertices.
    const uvec3 t = mesh.triangles[triangle];
    const vec3 p = (1.0f - b.x - b.y) * mesh.positions[t.x] + b.x * mesh.positions[t.y] +
                   b.y * mesh.positions[t.z];
    EXPECT_LT(glm::length(p - g.position[i]), 1e-4f) << i;
    EXPECT_EQ(g.motion[i], vec2(0.0f));
  }
  EXPECT_GT(hits, g.size() / 2);
}

}  // namespace
}  // namespace bounce
