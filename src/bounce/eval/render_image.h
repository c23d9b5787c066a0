// One still image from a technique named on the command line or in a test: builds the tracer, the
// technique and a Renderer, and accumulates frames. It sits above techniques/ because it creates
// one by name.
#pragma once

#include <string>

#include "bounce/core/image.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/scene.h"

namespace bounce {

// Renders `spp` jittered frames of the scene's own camera at rest, accumulating, and returns the
// last frame's linear colour: the pipeline's average of them.
Image render_image(const Scene& scene, const std::string& technique, const FrameSettings& settings,
                   int spp = 1);

}  // namespace bounce
