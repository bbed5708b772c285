// Parsing of the command-line options that keep one meaning in every verb (DESIGN.md §7):
// --res WxH, --camera px,py,pz:tx,ty,tz:vfov, --sun dx,dy,dz:E[:r,g,b][:angle],
// --sky r,g,b|daylight[:T].
// Bad text gets a bounce::Error naming the option and the expected form.
#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace bounce {

struct Resolution {
  uint32_t width = 0;
  uint32_t height = 0;
};

// "WxH" with 1 <= W, H <= 16384.
Resolution parseResolution(const std::string& text);
// "px,py,pz:tx,ty,tz:vfov" in glTF space (+Y up), vertical FOV in degrees (0, 180).
Camera parseCamera(const std::string& text);
// "dx,dy,dz:E[:r,g,b][:angle_deg]": direction the light travels, irradiance E >= 0.
Sun parseSun(const std::string& text);
// "r,g,b", each finite and >= 0.
glm::vec3 parseRgb(const std::string& text, const std::string& option);
// --sky: "r,g,b" (constant radiance) or "daylight[:T]" (Preetham sky lit by the sun, turbidity
// T in [2, 10], default 3).
Sky parseSky(const std::string& text);

// What the common options change in a loaded scene.
struct SceneOverrides {
  std::optional<Camera> camera;
  std::optional<Sun> sun;
  std::optional<Sky> sky;
};
void applyOverrides(Scene& scene, const SceneOverrides& overrides);

// The scene's camera, else a default framing of its bounds.
Camera effectiveCamera(const Scene& scene);

}  // namespace bounce
