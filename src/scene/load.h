// Where scenes come from: a built-in procedural scene by name, or a glTF 2.0 file.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/load_warnings.h"
#include "scene/scene.h"

namespace bounce {

// glTF 2.0 (.gltf with external or embedded buffers, or .glb). Throws bounce::Error naming the
// file and the problem for anything malformed or unsupported. Problems it can work around
// (degenerate geometry, ignored features: docs/scenes.md) become warnings: collected in
// `warnings`, or printed to stderr as a summary by the one-argument form.
// (src/scene/gltf_loader.cpp)
Scene loadGltf(const std::string& path, LoadWarnings& warnings);
Scene loadGltf(const std::string& path);

// Built-in procedural scenes (src/scene/procedural/). Names: cornell, sunroom,
// sunroom-glossy, foliage, manylights, furnace, city, city-10k, spheres.
std::vector<std::string> builtinSceneNames();
std::optional<Scene> makeBuiltinScene(const std::string& name);

// Whether `nameOrPath` names a glTF file (.gltf or .glb, any case) rather than a built-in scene.
bool isGltfPath(const std::string& nameOrPath);

// A built-in name, or a path ending in .gltf/.glb. Unknown names get an error listing the
// built-ins. (src/scene/load.cpp)
Scene loadScene(const std::string& nameOrPath);

}  // namespace bounce
