#include "common_options.h"

#include <cstdio>

#include "scene/default_light.h"
#include "scene/load.h"

namespace bounce::app {

void CommonOptions::addSceneOptions(CLI::App& cmd, const std::string& defaultScene) {
  scene = defaultScene;
  cmd.add_option("--scene", scene, "Built-in scene name or .gltf/.glb path")->capture_default_str();
  cmd.add_option("--camera", camera, "px,py,pz:tx,ty,tz:vfov (glTF space, +Y up, degrees)");
  cmd.add_option("--sun", sun, "dx,dy,dz:E[:r,g,b][:angle_deg] (direction of travel, irradiance)");
  cmd.add_option("--sky", sky,
                 "r,g,b constant sky radiance, or daylight[:T] for the Preetham sky lit by the sun "
                 "(turbidity T in [2, 10], default 3)");
}

void CommonOptions::addDeviceOptions(CLI::App& cmd) {
  cmd.add_option("--device", device, "Vulkan device index (see `bounce info`); or BOUNCE_DEVICE");
  cmd.add_flag("--validate", validate,
               "Enable Vulkan validation (incl. synchronization); any error -> exit code 4");
}

void CommonOptions::addResolution(CLI::App& cmd, const std::string& defaultRes) {
  res = defaultRes;
  cmd.add_option("--res", res, "Image size WxH")->capture_default_str();
}

Scene CommonOptions::loadScene() const {
  Scene s = bounce::loadScene(scene);
  SceneOverrides overrides;
  if (!camera.empty()) overrides.camera = parseCamera(camera);
  if (!sun.empty()) overrides.sun = parseSun(sun);
  if (!sky.empty()) overrides.sky = parseSky(sky);
  applyOverrides(s, overrides);
  if (std::optional<std::string> note = applyDefaultLight(s, overrides, scene))
    std::fprintf(stderr, "note: %s\n", note->c_str());
  return s;
}

Resolution CommonOptions::resolution() const {
  return parseResolution(res);
}

std::unique_ptr<vk::Context> CommonOptions::createContext() const {
  vk::ContextOptions options;
  options.deviceIndex = device;
  options.validation = validate;
  options.synchronizationValidation = validate;
  options = vk::contextOptionsFromEnvironment(options);
  return std::make_unique<vk::Context>(options);
}

int exitCodeFor(const vk::Context& context) {
  if (context.validationErrorCount() == 0) return 0;
  std::fprintf(stderr, "bounce: error: %u Vulkan validation error(s)\n",
               context.validationErrorCount());
  return kValidationFailedExit;
}

}  // namespace bounce::app
