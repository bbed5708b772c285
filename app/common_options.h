// Options that keep one meaning in every verb (DESIGN.md §7), registered once and turned into
// a loaded scene and a Vulkan context.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "scene/scene.h"
#include "scene/scene_options.h"
#include "vk/context.h"

namespace bounce::app {

struct CommonOptions {
  std::string scene = "cornell";
  std::string res;
  std::string camera;
  std::string sun;
  std::string sky;
  std::optional<uint32_t> device;
  bool validate = false;
  uint64_t seed = 1;

  // Which options a verb offers.
  void addSceneOptions(CLI::App& cmd, const std::string& defaultScene);
  void addDeviceOptions(CLI::App& cmd);
  void addResolution(CLI::App& cmd, const std::string& defaultRes);

  Scene loadScene() const;  // --scene plus --camera/--sun/--sky overrides
  Resolution resolution() const;
  std::unique_ptr<vk::Context> createContext() const;
};

// Exit code for a run whose validation layer reported errors.
constexpr int kValidationFailedExit = 4;
int exitCodeFor(const vk::Context& context);

}  // namespace bounce::app
