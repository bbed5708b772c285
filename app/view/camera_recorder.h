// Records the viewer's camera as a camera path: a key every `interval` seconds of wall time
// while recording, written as the JSON that `bounce render --camera-path` reads
// (scene/animation.h, docs/cli.md): {"keyframes": [{"time", "position", "target", "vfov",
// "cut"}], "loop": false, "interpolation": "catmull-rom"}.
#pragma once
#include <string>
#include <vector>

#include "scene/animation.h"
#include "scene/scene.h"

namespace bounce::view {

class CameraRecorder {
 public:
  explicit CameraRecorder(float interval = 0.25f) : interval_(interval) {}

  void start();
  // Adds a key when `seconds` (since start, not decreasing) is at least `interval` after the
  // last one, or when it is the first. Keys where the camera did not move are kept: a pause
  // is part of a path.
  void update(float seconds, const Camera& camera);
  bool recording() const { return recording_; }
  // Stops and returns the path recorded (no keys if nothing was recorded).
  CameraPath stop();
  size_t keyCount() const { return path_.keys.size(); }

 private:
  float interval_;
  bool recording_ = false;
  CameraPath path_;
};

// The JSON of `path` in loadCameraPath's format.
std::string cameraPathJson(const CameraPath& path);

}  // namespace bounce::view
