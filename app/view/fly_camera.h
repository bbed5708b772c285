// The viewer's camera: fly (WASD moves, the mouse turns the view) or orbit (the mouse turns the
// camera around a pivot, the wheel moves it nearer or farther). Pure maths on the scene's
// conventions (+Y up, metres); the window's input is turned into these calls by the viewer.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace bounce::view {

enum class CameraMode { Fly, Orbit };

class FlyCamera {
 public:
  FlyCamera() = default;
  // Starts at `camera`, looking where it looks; its target becomes the orbit pivot.
  explicit FlyCamera(const Camera& camera);

  // Fly: moves by (right, up, forward) * metres along the view's axes (forward is the view
  // direction, up is world +Y). Orbit: pans the pivot and the camera together.
  void move(const glm::vec3& rightUpForward);
  // Turns the view direction by yaw to the right and pitch up, in radians. Fly: the view turns
  // about the camera; orbit: the camera moves around the pivot at the same distance so that it
  // still looks at it (pitching up puts the camera below the pivot). Pitch stays within +-89 deg.
  void turn(float yawRight, float pitchUp);
  // Orbit: multiplies the distance to the pivot by `factor` (> 0, at least 1 mm); fly: moves
  // forward by (1 - factor) times the pivot distance.
  void zoom(float factor);

  void setMode(CameraMode mode);
  CameraMode mode() const { return mode_; }
  Camera camera() const;
  glm::vec3 forward() const;
  float verticalFovDegrees = 45.0f;

 private:
  glm::vec3 position_{0.0f, 0.0f, 5.0f};
  float yaw_ = 0.0f;       // 0 looks towards -Z, positive turns towards +X
  float pitch_ = 0.0f;     // positive looks up
  float distance_ = 5.0f;  // to the pivot, along forward
  CameraMode mode_ = CameraMode::Fly;
};

}  // namespace bounce::view
