#include "bounce/eval/temporal_runs.h"

#include <algorithm>

#include "bounce/core/error.h"
#include "bounce/scene/scene_edit.h"
#include "bounce/trace/tracer.h"

namespace bounce {

SceneChange move_first_light(Scene& scene, vec3 offset, std::string* moved) {
  for (Light& light : scene.lights) {
    if (light.type == LightType::kDirectional) continue;
    light.position += offset;
    scene.derive();
    if (moved) *moved = light.name;
    SceneChange change;
    change.lights = true;
    return change;
  }
  if (scene.area_lights.empty()) return SceneChange{};
  if (moved) *moved = scene.area_lights.front().name;
  return move_area_light(scene, 0, offset);
}

bool has_movable_light(const Scene& scene) {
  for (const Light& light : scene.lights)
    if (light.type != LightType::kDirectional) return true;
  return !scene.area_lights.empty();
}

FlickerResult measure_flicker(const Scene& scene, const TechniqueFactory& make,
                              FrameSettings settings, int warmup, int frames, bool accumulate,
                              const DenoiseSettings& denoise) {
  if (frames < 1) fail("flicker needs at least one frame (got {})", frames);
  FlickerResult result;
  std::unique_ptr<Technique> technique = make();
  settings.accumulate = accumulate;
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, std::move(technique));
  renderer.denoiser().settings() = denoise;
  for (int k = 0; k < warmup; ++k) renderer.render(scene.camera, settings);
  FlickerAccumulator acc;
  for (int k = 0; k < frames; ++k) acc.add(renderer.render(scene.camera, settings).color);
  result.flicker = acc.flicker();
  result.mean_deviation = acc.mean_deviation();
  result.mean_value = acc.mean_value();
  return result;
}

SettleResult measure_settle(const Scene& original, const TechniqueFactory& make,
                            FrameSettings settings, const SettleOptions& o,
                            const DenoiseSettings& denoise) {
  if (o.rest_frames < 0 || o.frames < 1 || o.target_frames < 1)
    fail("settle: frame counts must be positive (rest {}, measured {}, target {})", o.rest_frames,
         o.frames, o.target_frames);
  SettleResult result;
  std::unique_ptr<Technique> technique = make();
  if (!technique->has_indirect()) {
    result.reason = "technique '" + technique->name() + "' has no indirect light";
    return result;
  }
  const float length = glm::length(o.direction);
  if (!(length > 0.0f)) fail("settle: the direction of the light's move is zero");
  if (!has_movable_light(original)) {
    result.reason = "scene '" + original.source + "' has no light that can move";
    return result;
  }
  Scene scene = original;  // the light moves in this copy
  result.offset = o.direction * (o.move_fraction * scene.bounds.diagonal() / length);
  result.applicable = true;
  settings.accumulate = true;
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, std::move(technique));
  renderer.denoiser().settings() = denoise;

  Image before;
  for (int k = 0; k < o.rest_frames; ++k) {
    const Frame& f = renderer.render(scene.camera, settings);
    if (k == o.rest_frames - 1) before = f.indirect;
  }
  renderer.scene_changed(move_first_light(scene, result.offset, &result.light));

  std::vector<BlockSums> after;
  after.reserve(size_t(o.frames));
  for (int k = 0; k < o.frames; ++k)
    after.push_back(block_sums(renderer.render(scene.camera, settings).indirect, o.block));
  Image target(settings.width, settings.height);
  for (int k = 0; k < o.target_frames; ++k)
    target += renderer.render(scene.camera, settings).indirect;
  target *= 1.0f / float(o.target_frames);

  const BlockSums target_sums = block_sums(target, o.block);
  for (const BlockSums& f : after) result.errors.push_back(block_error(f, target_sums));
  result.settle_frame = settle_frame(result.errors, o.tolerance);
  result.change = before.empty() ? 0.0 : block_error(block_sums(before, o.block), target_sums);
  return result;
}

}  // namespace bounce
