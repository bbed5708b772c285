// Maps built-in scene names to the functions that build them.
#include <array>

#include "scene/load.h"
#include "scene/procedural/builtin_scenes.h"
#include "scene/procedural/furnace.h"

namespace bounce {

namespace {

struct BuiltinScene {
  const char* name;
  Scene (*make)();
};

Scene makeDefaultFurnace() {
  return makeFurnaceScene(0.5f, glm::vec3(1.0f));
}

constexpr std::array<BuiltinScene, 11> kBuiltinScenes = {{
    {"cornell", procedural::makeCornellScene},
    {"sunroom", procedural::makeSunroomScene},
    {"sunroom-glossy", procedural::makeGlossySunroomScene},
    {"foliage", procedural::makeFoliageScene},
    {"manylights", procedural::makeManyLightsScene},
    {"furnace", makeDefaultFurnace},
    {"city", procedural::makeCityScene},
    {"city-10k", procedural::makeCity10kScene},
    {"spheres", procedural::makeSpheresScene},
    {"skinned", procedural::makeSkinnedScene},
    {"skinned-crowd", procedural::makeSkinnedCrowdScene},
}};

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& builtin : kBuiltinScenes) names.emplace_back(builtin.name);
  return names;
}

std::optional<Scene> makeBuiltinScene(const std::string& name) {
  for (const BuiltinScene& builtin : kBuiltinScenes) {
    if (name != builtin.name) continue;
    Scene scene = builtin.make();
    scene.name = name;
    validateScene(scene, "built-in scene '" + name + "'");
    return scene;
  }
  return std::nullopt;
}

}  // namespace bounce
