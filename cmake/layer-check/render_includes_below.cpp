// Must compile: the render layer sees its own headers and those of the layers below it.
#include "bounce/core/image.h"
#include "bounce/render/renderer.h"
#include "bounce/scene/scene.h"
#include "bounce/trace/tracer.h"

int bounce_layer_check_right_way() {
  return int(sizeof(bounce::FrameSettings));
}
