// libFuzzer target: the image readers (src/tools/image_io: PNG and JPEG through stb, EXR
// through tinyexr) on arbitrary bytes, as .exr when they start with the OpenEXR magic and as
// .png otherwise (stb detects PNG and JPEG by content). A refused file is a bounce::Error;
// anything else is a bug.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"
#include "fuzz_input.h"
#include "tools/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const uint8_t kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  const bool exr = size >= 4 && std::memcmp(data, kExrMagic, 4) == 0;
  const std::string path = bounce::fuzz::writeInputFile("image", exr ? "exr" : "png", data, size);
  if (path.empty()) return 0;
  try {
    bounce::ImageRGBA32F image = bounce::readImage(path);
    (void)image;
    if (exr) (void)bounce::readExrMetadata(path);
  } catch (const bounce::Error&) {
  }
  return 0;
}
