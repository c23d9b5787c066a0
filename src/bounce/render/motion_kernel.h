// Per-pixel motion vectors: where the surface point a pixel sees was in the previous frame, so
// that temporal reuse can find its history. The previous frame's pose is the previous camera
// and, for meshes that moved, their previous vertex positions (MeshView::previous_positions).
#pragma once

#include <cstddef>

#include "bounce/core/device.h"
#include "bounce/core/lane.h"
#include "bounce/core/math.h"
#include "bounce/render/gbuffer_view.h"
#include "bounce/scene/camera.h"
#include "bounce/scene/scene_view.h"

namespace bounce {

// Motion of a point that was behind the previous camera: far off any image, so reprojection
// finds no history there (and small enough to convert to an int).
inline constexpr float kOffscreenMotion = 1.0e6f;

// Where pixel i's surface point was in world space in the previous frame: the same barycentric
// point of the same triangle in the mesh's previous pose, or the point itself when its mesh did
// not move.
BOUNCE_HD inline vec3 previous_position(const SceneView& scene, const ConstGBufferView& g,
                                        size_t i) {
  const uint32_t m = g.mesh[i];
  const MeshView& mesh = scene.meshes[m];
  if (mesh.previous_positions == nullptr) return g.position[i];
  const uvec3 t = mesh.triangles[g.primitive[i] - scene.triangle_offsets[m]];
  const vec2 b = g.barycentric[i];
  const vec3* p = mesh.previous_positions;
  return p[t.x] * (1.0f - b.x - b.y) + p[t.y] * b.x + p[t.z] * b.y;
}

// Pixel i's motion in pixels from the previous frame to this one: its continuous position now
// (through `current`) minus where its point projected through `previous`. Unjittered: a still
// camera over a still scene gives exactly zero. Pixels without a surface move as directions
// (the sky at infinity); a point behind the previous camera gets kOffscreenMotion.
BOUNCE_HD inline vec2 motion_pixel(const SceneView& scene, const CameraRays& current,
                                   const CameraRays& previous, const ConstGBufferView& g,
                                   size_t i) {
  const bool still_camera = current == previous;
  if (!g.hit(i)) {
    if (still_camera) return vec2(0.0f);
    const int x = int(i % size_t(g.width)), y = int(i / size_t(g.width));
    const vec3 d = current.direction(float(x) + 0.5f, float(y) + 0.5f);
    if (glm::dot(d, previous.forward) <= 0.0f) return vec2(kOffscreenMotion);
    return vec2(float(x) + 0.5f, float(y) + 0.5f) - previous.project(previous.origin + d);
  }
  const vec3 before = previous_position(scene, g, i);
  if (glm::dot(before - previous.origin, previous.forward) <= 0.0f) return vec2(kOffscreenMotion);
  // Exactly zero for a still point under a still camera (projection would round).
  if (still_camera && glm::all(glm::equal(before, g.position[i]))) return vec2(0.0f);
  return current.project(g.position[i]) - previous.project(before);
}

// motion_pixel at pixel (x, y) = i when the camera moved and no mesh did, branch-free so that a
// row loop vectorises: the same arithmetic, each pixel's case chosen by selects.
BOUNCE_HD BOUNCE_LANE_INLINE vec2 camera_motion_pixel(const CameraRays& current,
                                                      const CameraRays& previous,
                                                      const ConstGBufferView& g, size_t i, int x,
                                                      int y) {
  const bool hit = g.hit(i);
  const float px = float(x) + 0.5f, py = float(y) + 0.5f;
  const vec3 d = current.direction(px, py);
  const vec3 position = g.position[i];
  // A surface point moves as a point; a pixel without one as its direction (the sky).
  const vec3 before = pick(hit, position, previous.origin + d);
  const float ahead = pick(hit, glm::dot(position - previous.origin, previous.forward),
                           glm::dot(d, previous.forward));
  const vec2 now = current.project(position);
  const vec2 then = previous.project(before);
  const bool seen = ahead > 0.0f;
  return {pick(seen, pick(hit, now.x, px) - then.x, kOffscreenMotion),
          pick(seen, pick(hit, now.y, py) - then.y, kOffscreenMotion)};
}

}  // namespace bounce
