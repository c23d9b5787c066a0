// Primary visibility by rasterisation: the triangle each pixel's camera ray meets first, found by
// z-buffering the scene's triangles in screen space, as real-time renderers find it, instead of
// tracing a ray per pixel (a level at 1280 x 720: Embree's primary rays were about 10 of the
// G-buffer's 33 ms; docs/benchmarks.md). The raster only proposes a candidate triangle per
// pixel; the G-buffer then intersects the pixel's own ray with it (intersect_triangle), so a hit
// is where the ray meets the triangle, as a traced ray's is. Coverage is conservative (a pixel
// whose sample lies within a small margin of a triangle's edge counts as covered), so rounding
// never leaves a hole; where the ray misses the candidate after all (the margin), or the
// candidate's material has cut-outs, the G-buffer traces that pixel's ray as before.
#pragma once

#include <cstdint>
#include <vector>

#include "bounce/core/math.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene_view.h"
#include "bounce/trace/ray.h"
#include "bounce/trace/ray_triangle.h"

namespace bounce {

// One triangle (or a piece of one the near plane or the guard band clipped) set up for the
// raster, in pixel coordinates relative to its bounding box's corner (x0, y0).
struct RasterTriangle {
  float a[3], b[3], c[3];  // edge functions a x + b y + c, >= -margin[k] on the triangle
  float margin[3];
  float za, zb, zc;    // 1 / depth along the view axis, a plane in the same coordinates
  int x0, y0, x1, y1;  // pixel bounds, inclusive, within the image
  uint32_t mesh, triangle;
};

// Whether the raster pays for `triangles` at width x height. It sets up every triangle each frame
// and draws each one's pixels, where a ray per pixel pays only for the pixel; measured on the
// 2-core machine (docs/benchmarks.md, "Primary visibility by rasterisation"), the raster wins
// with more than about 16 pixels per triangle (an OpenArena level at 640 x 360 has 56, the
// Cornell box thousands) and loses with fewer (cubes:5000 at 512 x 512, 4.4 pixels a triangle:
// G-buffer 21 ms against 15 traced; a million triangles: 129 against 24).
inline constexpr uint64_t kRasterPixelsPerTriangle = 16;
inline bool raster_pays(uint64_t triangles, int width, int height) {
  return triangles * kRasterPixelsPerTriangle <= uint64_t(width) * uint64_t(height);
}

class PrimaryRaster {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFFu;

  // Rasterises the scene's triangles for pixel samples at (x + subpixel.x, y + subpixel.y).
  // Returns false when it cannot stand for the camera rays: geometry closer to the eye than the
  // near plane within the view (the caller then traces every pixel).
  bool build(const SceneView& scene, const CameraRays& camera, vec2 subpixel, int width,
             int height);
  // Per pixel (row-major): the index of its candidate in triangles(), or kNone.
  const uint32_t* candidates() const { return candidate_.data(); }
  const RasterTriangle* triangles() const { return triangles_.data(); }
  size_t triangle_count() const { return triangles_.size(); }

 private:
  std::vector<RasterTriangle> triangles_;
  std::vector<uint32_t> candidate_;
  std::vector<uint32_t> band_start_, band_list_;  // triangles per band of rows (counting sort)
};

}  // namespace bounce
