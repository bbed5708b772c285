// Options that keep one meaning in every verb (DESIGN.md §7), registered once and turned into
// a loaded scene and a Vulkan context; and the rules every verb follows with its options:
// which were given, refused pairs, enumerated values with a suggestion.
#pragma once
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "rt/gpu_scene.h"
#include "scene/scene.h"
#include "scene/scene_options.h"
#include "vk/context.h"

namespace bounce::app {

// The options given on the command line ("--camera", ...), for refusing conflicts: recorded
// by each verb's callback, after parsing.
struct GivenOptions {
  std::set<std::string> names;

  void record(const CLI::App& cmd);
  bool has(const std::string& option) const { return names.count(option) != 0; }
  // Throws bounce::Error "A and B cannot be used together: why" when both were given.
  void refuseTogether(const std::string& a, const std::string& b, const std::string& why) const;
};

struct CommonOptions {
  std::string scene = "cornell";
  std::string res;
  std::string camera;
  std::string sun;
  std::string sky;
  std::string bvh = "binary";  // --bvh: the BLAS node layout (rt::BvhLayout)
  // --tlas-rebuild-ratio: GpuSceneOptions::tlasRebuildRatio (0 = refit only, never rebuild)
  double tlasRebuildRatio = GpuSceneOptions{}.tlasRebuildRatio;
  std::optional<float> poseTime;  // --pose-time: the scene frozen at this animation time
  std::optional<uint32_t> device;
  bool validate = false;
  uint64_t deviceMemoryLimitMiB = 0;  // --device-memory-limit; 0: none
  GivenOptions given;

  // Which options a verb offers.
  void addSceneOptions(CLI::App& cmd, const std::string& defaultScene);
  void addDeviceOptions(CLI::App& cmd);
  void addResolution(CLI::App& cmd, const std::string& defaultRes);

  // Checks the scene options' text without loading anything (a scene name not built in gets a
  // suggestion), so that usage errors come before any work.
  void checkArguments() const;
  // --scene plus --camera/--sun/--sky overrides, frozen at --pose-time
  Scene loadScene() const;
  GpuSceneOptions gpuSceneOptions() const;  // --bvh, --tlas-rebuild-ratio
  Resolution resolution() const;
  std::unique_ptr<vk::Context> createContext() const;
};

// `value` must be one of `names` (enumerated option values: --gi, --preset, ...); otherwise
// bounce::Error "--gi 'evolv': expected one of none, evolve, cache (did you mean evolve?)".
void requireOneOf(const std::string& option, const std::string& value,
                  const std::vector<std::string>& names);

// Exit code for a run whose validation layer reported errors.
constexpr int kValidationFailedExit = 4;
int exitCodeFor(const vk::Context& context);

// What --animate plays (render, bench): the scene's own animation, with the default camera
// motion, a slow sway and dolly, where the scene has no camera path or `cameraGiven` (a
// --camera on the command line is where the sway starts, rather than being overridden).
SceneAnimation playedAnimation(const Scene& scene, bool cameraGiven);

// True on a CPU implementation (lavapipe), where GPU timestamps measure the emulation.
bool isCpuDevice(const vk::Context& context);

}  // namespace bounce::app
