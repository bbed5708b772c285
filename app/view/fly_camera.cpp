#include "fly_camera.h"

#include <algorithm>
#include <cmath>

namespace bounce::view {

namespace {
constexpr float kMaxPitch = 1.5533f;  // 89 degrees: the view never flips over the pole
constexpr float kMinDistance = 1e-3f;
}  // namespace

FlyCamera::FlyCamera(const Camera& camera)
    : verticalFovDegrees(camera.verticalFovDegrees), position_(camera.position) {
  glm::vec3 d = camera.target - camera.position;
  distance_ = std::max(glm::length(d), kMinDistance);
  d /= distance_;
  pitch_ = std::clamp(std::asin(std::clamp(d.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  yaw_ = std::atan2(d.x, -d.z);
}

glm::vec3 FlyCamera::forward() const {
  return {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), -std::cos(pitch_) * std::cos(yaw_)};
}

void FlyCamera::move(const glm::vec3& rightUpForward) {
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::vec3(std::cos(yaw_), 0.0f, std::sin(yaw_)));
  position_ +=
      right * rightUpForward.x + glm::vec3(0, 1, 0) * rightUpForward.y + f * rightUpForward.z;
}

void FlyCamera::turn(float yawRight, float pitchUp) {
  const glm::vec3 pivot = position_ + forward() * distance_;
  yaw_ += yawRight;
  pitch_ = std::clamp(pitch_ + pitchUp, -kMaxPitch, kMaxPitch);
  if (mode_ == CameraMode::Orbit) position_ = pivot - forward() * distance_;
}

void FlyCamera::zoom(float factor) {
  if (!(factor > 0.0f)) return;
  const glm::vec3 pivot = position_ + forward() * distance_;
  const float next = std::max(distance_ * factor, kMinDistance);
  if (mode_ == CameraMode::Orbit) {
    distance_ = next;
    position_ = pivot - forward() * distance_;
  } else {
    position_ += forward() * (distance_ - next);
  }
}

void FlyCamera::setMode(CameraMode mode) {
  mode_ = mode;
}

Camera FlyCamera::camera() const {
  Camera c;
  c.position = position_;
  c.target = position_ + forward() * distance_;
  c.verticalFovDegrees = verticalFovDegrees;
  return c;
}

}  // namespace bounce::view
