// libFuzzer target: the glTF 2.0 loader (src/scene) on arbitrary bytes, as a .glb when they
// start with the GLB magic and as a .gltf otherwise. The loader may refuse a file, with a
// bounce::Error naming what is wrong; anything else (a crash, a sanitizer report, a hang, an
// exception of another type) is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"
#include "scene/load.h"
#include "scene/load_warnings.h"

namespace {

// One file per process, rewritten for each input: the loader reads paths, not memory.
std::string inputPath(bool glb) {
  static const std::string base = "/tmp/bounce-fuzz-gltf-" + std::to_string(getpid());
  return base + (glb ? ".glb" : ".gltf");
}

bool writeFile(const std::string& path, const uint8_t* data, size_t size) {
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return false;
  const bool ok = std::fwrite(data, 1, size, file) == size;
  return std::fclose(file) == 0 && ok;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = inputPath(glb);
  if (!writeFile(path, data, size)) return 0;
  try {
    bounce::LoadWarnings warnings;
    bounce::Scene scene = bounce::loadGltf(path, warnings);
    (void)scene;
  } catch (const bounce::Error&) {
    // A refused file: the expected outcome for most inputs.
  }
  return 0;
}
