// What a caller that feeds a library denoiser from the CPU needs (bounce::Denoiser in src/api/,
// the denoisers' tests): images the frame graph can import as the denoiser's inputs, and the
// bytes vk::uploadImage takes for their fp16 formats.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "vk/resources.h"

namespace bounce {

// A 2D image with the storage and sampled usages (the frame graph reads imported inputs as
// sampled images, shader-read-only layout) that transfers can fill and read.
vk::Image denoiseInputImage(vk::Context& context, VkFormat format, uint32_t width, uint32_t height,
                            const char* name);

// `values` as fp16, 2 bytes each.
std::vector<uint8_t> halfBytes(std::span<const float> values);

}  // namespace bounce
