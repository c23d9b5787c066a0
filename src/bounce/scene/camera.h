// Pinhole camera. Pixel (0, 0) is the top-left; pixel coordinates are continuous, so pixel
// (x, y) covers [x, x+1) x [y, y+1) and its centre is (x + 0.5, y + 0.5).
#pragma once

#include "bounce/core/device.h"
#include "bounce/core/math.h"

namespace bounce {

struct Camera {
  vec3 position{0.0f, 0.0f, 0.0f};
  vec3 look_at{0.0f, 0.0f, 1.0f};
  vec3 up{0.0f, 1.0f, 0.0f};
  float vfov_deg = 45.0f;  // vertical field of view

  bool operator==(const Camera&) const = default;
};

// A camera prepared for an image size: maps pixel coordinates to ray directions.
struct CameraRays {
  vec3 origin;
  vec3 forward;  // unit view direction
  vec3 right;    // image +x, scaled to half the image plane width at distance 1
  vec3 up;       // image -y (towards the top), scaled to half the image plane height
  float width = 1.0f;
  float height = 1.0f;

  bool operator==(const CameraRays&) const = default;

  static CameraRays from(const Camera& camera, int width, int height);
  // Unit direction through the continuous pixel position (px, py).
  BOUNCE_HD vec3 direction(float px, float py) const {
    // Reciprocals a row loop hoists: no division per pixel.
    const float sx = px * (2.0f / width) - 1.0f;
    const float sy = 1.0f - py * (2.0f / height);
    return glm::normalize(forward + sx * right + sy * up);
  }
  // The angle one pixel spans at the image's centre, radians (small): a primary ray's cone.
  BOUNCE_HD float pixel_spread() const { return 2.0f * glm::length(up) / height; }
  // Continuous pixel position of a world point in front of the camera (inverse of direction).
  BOUNCE_HD vec2 project(vec3 p) const {
    const vec3 d = p - origin;
    const float z = glm::dot(d, forward);
    const float sx = glm::dot(d, right) / (z * glm::dot(right, right));
    const float sy = glm::dot(d, up) / (z * glm::dot(up, up));
    return {(sx + 1.0f) * 0.5f * width, (1.0f - sy) * 0.5f * height};
  }
};

}  // namespace bounce
