#include "bounce/eval/render_image.h"

#include "bounce/core/error.h"
#include "bounce/techniques/registry.h"
#include "bounce/trace/tracer.h"

namespace bounce {

Image render_image(const Scene& scene, const std::string& technique, const FrameSettings& settings,
                   int spp) {
  if (spp <= 0) fail("samples per pixel must be positive (got {})", spp);
  auto tracer = make_embree_tracer(scene);
  Renderer renderer(scene, *tracer, make_technique(technique));
  FrameSettings s = settings;
  s.jitter = spp > 1;
  s.accumulate = spp > 1;  // the frames at rest average in the pipeline, once
  for (int k = 0; k + 1 < spp; ++k) renderer.render(scene.camera, s);
  return renderer.render(scene.camera, s).color;
}

}  // namespace bounce
