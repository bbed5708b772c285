// libFuzzer target: the glTF 2.0 loader (src/scene) on arbitrary bytes, as a .glb when they
// start with the GLB magic and as a .gltf otherwise. The loader may refuse a file, with a
// bounce::Error naming what is wrong; anything else (a crash, a sanitizer report, a hang, an
// exception of another type) is a bug.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"
#include "fuzz_input.h"
#include "scene/load.h"
#include "scene/load_warnings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = bounce::fuzz::writeInputFile("gltf", glb ? "glb" : "gltf", data, size);
  if (path.empty()) return 0;
  try {
    bounce::LoadWarnings warnings;
    bounce::Scene scene = bounce::loadGltf(path, warnings);
    (void)scene;
  } catch (const bounce::Error&) {
    // A refused file: the expected outcome for most inputs.
  }
  return 0;
}
