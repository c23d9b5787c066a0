#include "bounce/interactive/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {
constexpr float kMaxPitch = 89.0f * kPi / 180.0f;
}

FlyCamera::FlyCamera(const Camera& camera)
    : position_(camera.position), vfov_deg_(camera.vfov_deg) {
  vec3 d = camera.look_at - camera.position;
  const float len = glm::length(d);
  d = len > 0.0f ? d / len : vec3(0.0f, 0.0f, 1.0f);
  pitch_ = std::clamp(std::asin(std::clamp(d.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  yaw_ = std::atan2(d.x, d.z);
}

vec3 FlyCamera::forward() const {
  return {std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), std::cos(yaw_) * std::cos(pitch_)};
}

vec3 FlyCamera::right() const {
  return glm::normalize(glm::cross(forward(), vec3(0.0f, 1.0f, 0.0f)));
}

Camera FlyCamera::camera() const {
  Camera c;
  c.position = position_;
  c.look_at = position_ + forward();
  c.up = vec3(0.0f, 1.0f, 0.0f);
  c.vfov_deg = vfov_deg_;
  return c;
}

void FlyCamera::move(vec3 local) {
  position_ += local.x * right() + local.y * vec3(0.0f, 1.0f, 0.0f) + local.z * forward();
}

void FlyCamera::turn(float yaw_deg, float pitch_deg) {
  // The image's +x is cross(forward, up), which for yaw 0 (looking along +z) is -x: turning
  // towards it decreases the angle atan2(x, z).
  yaw_ -= glm::radians(yaw_deg);
  yaw_ = std::remainder(yaw_, kTwoPi);
  pitch_ = std::clamp(pitch_ + glm::radians(pitch_deg), -kMaxPitch, kMaxPitch);
}

}  // namespace bounce
