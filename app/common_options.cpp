#include "common_options.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "scene/animation.h"
#include "scene/default_light.h"
#include "scene/deformation.h"
#include "scene/load.h"
#include "suggest.h"

namespace bounce::app {

void GivenOptions::record(const CLI::App& cmd) {
  for (const CLI::Option* option : cmd.get_options())
    if (option->count() > 0) names.insert(option->get_name());
}

void GivenOptions::refuseTogether(const std::string& a, const std::string& b,
                                  const std::string& why) const {
  if (has(a) && has(b)) fail("{} and {} cannot be used together: {}", a, b, why);
}

void requireOneOf(const std::string& option, const std::string& value,
                  const std::vector<std::string>& names) {
  if (std::find(names.begin(), names.end(), value) != names.end()) return;
  fail("{} '{}': expected one of {}{}", option, value, joinNames(names), didYouMean(value, names));
}

void CommonOptions::addSceneOptions(CLI::App& cmd, const std::string& defaultScene) {
  scene = defaultScene;
  cmd.add_option("--scene", scene, "Built-in scene name or .gltf/.glb path")->capture_default_str();
  cmd.add_option("--camera", camera, "px,py,pz:tx,ty,tz:vfov (glTF space, +Y up, degrees)");
  cmd.add_option("--sun", sun, "dx,dy,dz:E[:r,g,b][:angle_deg] (direction of travel, irradiance)");
  cmd.add_option("--sky", sky,
                 "r,g,b constant sky radiance, or daylight[:T] for the Preetham sky lit by the sun "
                 "(turbidity T in [2, 10], default 3)");
  cmd.add_option("--pose-time", poseTime,
                 "Freeze the scene at this animation time in seconds: moving objects, lights, "
                 "skinned and morphed meshes placed as then and still from there (e.g. a "
                 "reference of one animated frame); docs/scenes.md")
      ->check(CLI::Range(0.0f, 1e6f));
  cmd.add_option("--bvh", bvh,
                 "BLAS node layout: binary (2-wide) or wide (8-wide compressed, Ylitie et al. "
                 "2017); docs/ray-tracing.md")
      ->capture_default_str();
  cmd.add_option("--tlas-rebuild-ratio", tlasRebuildRatio,
                 "Rebuild the GPU-refitted TLAS of moving instances when its SAH cost has grown "
                 "this many times since its last build; 0 = never (docs/ray-tracing.md)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
}

GpuSceneOptions CommonOptions::gpuSceneOptions() const {
  return GpuSceneOptions{.bvhLayout = rt::parseBvhLayout(bvh),
                         .tlasRebuildRatio = tlasRebuildRatio};
}

void CommonOptions::addDeviceOptions(CLI::App& cmd) {
  cmd.add_option("--device", device, "Vulkan device index (see `bounce info`); or BOUNCE_DEVICE");
  cmd.add_flag("--validate", validate,
               "Enable Vulkan validation (incl. synchronization); any error -> exit code 4");
  cmd.add_option("--device-memory-limit", deviceMemoryLimitMiB,
                 "Fail, as out of memory, any allocation beyond this many MiB of device memory "
                 "(to check a preset against a smaller GPU); or BOUNCE_DEVICE_MEMORY_LIMIT")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 24));
}

void CommonOptions::addResolution(CLI::App& cmd, const std::string& defaultRes) {
  res = defaultRes;
  cmd.add_option("--res", res, "Image size WxH")->capture_default_str();
}

namespace {

SceneOverrides parseOverrides(const CommonOptions& o) {
  SceneOverrides overrides;
  if (!o.camera.empty()) overrides.camera = parseCamera(o.camera);
  if (!o.sun.empty()) overrides.sun = parseSun(o.sun);
  if (!o.sky.empty()) overrides.sky = parseSky(o.sky);
  return overrides;
}

}  // namespace

void CommonOptions::checkArguments() const {
  if (!isGltfPath(scene)) {
    const std::vector<std::string> builtins = builtinSceneNames();
    if (std::find(builtins.begin(), builtins.end(), scene) == builtins.end())
      fail("--scene '{}': not a built-in scene ({}) nor a .gltf/.glb path{}", scene,
           joinNames(builtins), didYouMean(scene, builtins));
  }
  if (!res.empty()) parseResolution(res);
  requireOneOf("--bvh", bvh, {"binary", "wide"});
  parseOverrides(*this);
}

Scene CommonOptions::loadScene() const {
  Scene s = bounce::loadScene(scene);
  if (poseTime) s = sceneFrozenAt(s, *poseTime);
  const SceneOverrides overrides = parseOverrides(*this);
  applyOverrides(s, overrides);
  // Built-in scenes are lit as designed (the furnace by its walls' radiance 1).
  if (isGltfPath(scene))
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
  options.memoryLimitBytes = deviceMemoryLimitMiB << 20;
  options = vk::contextOptionsFromEnvironment(options);
  return std::make_unique<vk::Context>(options);
}

int exitCodeFor(const vk::Context& context) {
  if (context.validationErrorCount() == 0) return 0;
  std::fprintf(stderr, "bounce: error: %u Vulkan validation error(s)\n",
               context.validationErrorCount());
  return kValidationFailedExit;
}

SceneAnimation playedAnimation(const Scene& scene, bool cameraGiven) {
  SceneAnimation animation = scene.animation;
  if (!animation.camera || cameraGiven)
    animation.camera = swayCameraPath(effectiveCamera(scene), 4.0f, 0.3f, 8.0f);
  return animation;
}

bool isCpuDevice(const vk::Context& context) {
  return context.info().type == "cpu";
}

}  // namespace bounce::app
