// Uses the installed library: renders the built-in Cornell box at a tiny size.
#include <bounce/eval/render_image.h>
#include <bounce/scene/load.h>

#include <cstdio>

int main() {
  const bounce::Scene scene = bounce::load_scene("cornell");
  bounce::FrameSettings settings;
  settings.width = 16;
  settings.height = 16;
  settings.light_samples = 1;
  const bounce::Image image = bounce::render_image(scene, "direct", settings);
  const bounce::vec3 m = bounce::mean(image);
  std::printf("mean radiance %f %f %f\n", m.x, m.y, m.z);
  return m.x > 0.0f ? 0 : 1;
}
