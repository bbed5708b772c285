#include "scene/scene_options.h"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/error.h"

namespace bounce {

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

bool parseFloat(const std::string& text, float& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  out = std::strtof(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(out);
}

glm::vec3 parseVec3(const std::string& text, const std::string& option, const std::string& form) {
  std::vector<std::string> parts = split(text, ',');
  glm::vec3 v;
  if (parts.size() != 3 || !parseFloat(parts[0], v.x) || !parseFloat(parts[1], v.y) ||
      !parseFloat(parts[2], v.z))
    fail("{} '{}': expected {}", option, text, form);
  return v;
}

float parseScalar(const std::string& text, const std::string& option, const std::string& form) {
  float v;
  if (!parseFloat(text, v)) fail("{} '{}': expected {}", option, text, form);
  return v;
}

}  // namespace

Resolution parseResolution(const std::string& text) {
  size_t x = text.find('x');
  if (x == std::string::npos) fail("--res '{}': expected WxH, e.g. 640x360", text);
  std::string w = text.substr(0, x), h = text.substr(x + 1);
  char* endW = nullptr;
  char* endH = nullptr;
  long width = std::strtol(w.c_str(), &endW, 10);
  long height = std::strtol(h.c_str(), &endH, 10);
  if (w.empty() || h.empty() || *endW || *endH)
    fail("--res '{}': expected WxH, e.g. 640x360", text);
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    fail("--res '{}': width and height must be in 1..16384", text);
  return {uint32_t(width), uint32_t(height)};
}

Camera parseCamera(const std::string& text) {
  const std::string form = "px,py,pz:tx,ty,tz:vfov (position, target, vertical FOV in degrees)";
  std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 3) fail("--camera '{}': expected {}", text, form);
  Camera cam;
  cam.position = parseVec3(parts[0], "--camera", form);
  cam.target = parseVec3(parts[1], "--camera", form);
  cam.verticalFovDegrees = parseScalar(parts[2], "--camera", form);
  if (!(cam.verticalFovDegrees > 0.0f && cam.verticalFovDegrees < 180.0f))
    fail("--camera '{}': vertical FOV must be in (0, 180) degrees", text);
  if (glm::length(cam.target - cam.position) <= 0.0f)
    fail("--camera '{}': position and target must differ", text);
  glm::vec3 forward = glm::normalize(cam.target - cam.position);
  if (std::abs(forward.y) > 0.9999f) cam.up = glm::vec3(0, 0, forward.y > 0 ? -1.0f : 1.0f);
  return cam;
}

Sun parseSun(const std::string& text) {
  const std::string form = "dx,dy,dz:E[:r,g,b][:angle_deg]";
  std::vector<std::string> parts = split(text, ':');
  if (parts.size() < 2 || parts.size() > 4) fail("--sun '{}': expected {}", text, form);
  Sun sun;
  glm::vec3 d = parseVec3(parts[0], "--sun", form);
  if (glm::length(d) <= 0.0f) fail("--sun '{}': the direction must not be zero", text);
  sun.direction = glm::normalize(d);
  sun.irradiance = parseScalar(parts[1], "--sun", form);
  if (sun.irradiance < 0.0f) fail("--sun '{}': irradiance E must be >= 0", text);
  for (size_t i = 2; i < parts.size(); ++i) {
    if (parts[i].find(',') != std::string::npos) {
      sun.color = parseRgb(parts[i], "--sun");
    } else {
      sun.angularDiameterDegrees = parseScalar(parts[i], "--sun", form);
      if (sun.angularDiameterDegrees < 0.0f || sun.angularDiameterDegrees > 90.0f)
        fail("--sun '{}': angular diameter must be in [0, 90] degrees", text);
    }
  }
  return sun;
}

glm::vec3 parseRgb(const std::string& text, const std::string& option) {
  glm::vec3 c = parseVec3(text, option, "r,g,b (three numbers >= 0)");
  if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
    fail("{} '{}': colour components must be >= 0", option, text);
  return c;
}

Sky parseSky(const std::string& text) {
  Sky sky;
  const std::string daylight = "daylight";
  if (text.compare(0, daylight.size(), daylight) != 0) {
    sky.radiance = parseRgb(text, "--sky");
    return sky;
  }
  sky.model = SkyModel::Daylight;
  if (text.size() == daylight.size()) return sky;
  const std::string form = "r,g,b or daylight[:T] (turbidity T in [2, 10])";
  if (text[daylight.size()] != ':') fail("--sky '{}': expected {}", text, form);
  sky.turbidity = parseScalar(text.substr(daylight.size() + 1), "--sky", form);
  if (sky.turbidity < 2.0f || sky.turbidity > 10.0f)
    fail("--sky '{}': turbidity must be in [2, 10], the range of the daylight model", text);
  return sky;
}

void applyOverrides(Scene& scene, const SceneOverrides& overrides) {
  if (overrides.camera) scene.camera = overrides.camera;
  if (overrides.sun) scene.sun = *overrides.sun;
  if (overrides.sky) scene.sky = *overrides.sky;
}

Camera effectiveCamera(const Scene& scene) {
  return scene.camera ? *scene.camera : defaultCamera(scene);
}

}  // namespace bounce
