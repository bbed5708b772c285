// Images read back from a Renderer, and writing them to files.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bounce/config.h"

namespace bounce::api {

// Float RGBA, rows top to bottom. What the values mean depends on the image (Renderer::readImage).
struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;  // 4 floats per pixel

  const float* pixel(uint32_t x, uint32_t y) const {
    return rgba.data() + 4 * (size_t(y) * width + x);
  }
};

// By extension: .png writes 8-bit sRGB (values clamped to [0, 1], then the sRGB transfer
// function: right for the linear display values of "tonemap"); .exr writes 32-bit float as is.
// Creates no directories. Throws bounce::Error when the file cannot be written or the extension
// is neither.
void writeImage(const std::string& path, const Image& image);

}  // namespace bounce::api
