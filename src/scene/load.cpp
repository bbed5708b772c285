#include "scene/load.h"

#include <filesystem>

#include "core/error.h"

namespace bounce {

bool isGltfPath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

Scene loadScene(const std::string& nameOrPath) {
  if (isGltfPath(nameOrPath)) return loadGltf(nameOrPath);
  if (std::optional<Scene> builtin = makeBuiltinScene(nameOrPath)) return std::move(*builtin);
  std::string names;
  for (const std::string& n : builtinSceneNames()) names += (names.empty() ? "" : ", ") + n;
  fail("--scene '{}': not a built-in scene ({}) nor a .gltf/.glb path", nameOrPath, names);
}

}  // namespace bounce
