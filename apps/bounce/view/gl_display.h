// Shows the engine's tone-mapped frame in the window through OpenGL 3.3 core: one texture, one
// full-window triangle, linear filtering when the internal resolution is scaled down. Also
// reads the window back for screenshots.
#pragma once

#include <cstdint>
#include <vector>

namespace bounce::app {

class GlDisplay {
 public:
  GlDisplay();  // needs a current OpenGL 3.3 core context
  ~GlDisplay();
  GlDisplay(const GlDisplay&) = delete;
  GlDisplay& operator=(const GlDisplay&) = delete;

  // Uploads an sRGB8 image (3 bytes per pixel, top row first).
  void upload(const uint8_t* rgb, int width, int height);
  // Draws the last upload over the whole framebuffer.
  void draw(int framebuffer_width, int framebuffer_height);
  // The framebuffer being drawn as sRGB8, top row first.
  static std::vector<uint8_t> read_back(int width, int height);

 private:
  unsigned program_ = 0, vao_ = 0, texture_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace bounce::app
