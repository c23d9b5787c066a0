// A first-person fly camera: a position, a heading (yaw) and a pitch, with +y up. Viewers and
// scripted runs move it; camera() turns it into the pipeline's Camera.
#pragma once

#include "bounce/core/math.h"
#include "bounce/scene/camera.h"

namespace bounce {

class FlyCamera {
 public:
  FlyCamera() = default;
  // Takes position, view direction and field of view from a scene camera.
  explicit FlyCamera(const Camera& camera);

  Camera camera() const;
  vec3 position() const { return position_; }
  vec3 forward() const;  // unit view direction
  vec3 right() const;    // unit image +x (as CameraRays: cross(forward, up))
  float yaw_deg() const { return glm::degrees(yaw_); }
  float pitch_deg() const { return glm::degrees(pitch_); }
  float vfov_deg() const { return vfov_deg_; }

  // Moves by `local` metres along (right, up, forward); up is world +y.
  void move(vec3 local);
  // Turns by yaw (about +y; positive turns towards the image's right) and pitch (positive looks
  // up) in degrees; pitch stays within +-89 degrees so the view never flips.
  void turn(float yaw_deg, float pitch_deg);
  void set_position(vec3 p) { position_ = p; }

 private:
  vec3 position_{0.0f};
  float yaw_ = 0.0f;    // radians; 0 looks along +z
  float pitch_ = 0.0f;  // radians
  float vfov_deg_ = 45.0f;
};

}  // namespace bounce
