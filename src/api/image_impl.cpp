#include <bounce/image.h>

#include "api/convert.h"
#include "core/error.h"

namespace bounce::api {

void writeImage(const std::string& path, const Image& image) {
  if (!isLdrExtension(path) && !isHdrExtension(path))
    fail("bounce::writeImage('{}'): expected a path ending in .png or .exr", path);
  bounce::writeImage(path, toInternal(image, "bounce::writeImage"));
}

}  // namespace bounce::api
