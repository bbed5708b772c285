#include "camera_recorder.h"

#include <nlohmann/json.hpp>

namespace bounce::view {

void CameraRecorder::start() {
  path_ = CameraPath{};
  path_.loop = false;
  path_.catmullRom = true;
  recording_ = true;
}

void CameraRecorder::update(float seconds, const Camera& camera) {
  if (!recording_) return;
  if (!path_.keys.empty() && seconds < path_.keys.back().time + interval_) return;
  CameraKeyframe key;
  key.time = seconds;
  key.position = camera.position;
  key.target = camera.target;
  key.verticalFovDegrees = camera.verticalFovDegrees;
  path_.keys.push_back(key);
}

CameraPath CameraRecorder::stop() {
  recording_ = false;
  return path_;
}

std::string cameraPathJson(const CameraPath& path) {
  nlohmann::json keys = nlohmann::json::array();
  auto vec = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  for (const CameraKeyframe& k : path.keys)
    keys.push_back({{"time", k.time},
                    {"position", vec(k.position)},
                    {"target", vec(k.target)},
                    {"vfov", k.verticalFovDegrees},
                    {"cut", k.cut}});
  nlohmann::json j;
  j["keyframes"] = keys;
  j["loop"] = path.loop;
  j["interpolation"] = path.catmullRom ? "catmull-rom" : "linear";
  return j.dump(2) + "\n";
}

}  // namespace bounce::view
