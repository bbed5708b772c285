#include "denoise/denoise_upload.h"

#include <cstring>

#include <glm/gtc/packing.hpp>

namespace bounce {

vk::Image denoiseInputImage(vk::Context& context, VkFormat format, uint32_t width, uint32_t height,
                            const char* name) {
  return vk::Image(context, format, width, height, 1, 1,
                   VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                       VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                   name, VK_IMAGE_VIEW_TYPE_2D);
}

std::vector<uint8_t> halfBytes(std::span<const float> values) {
  std::vector<uint8_t> bytes(values.size() * 2);
  for (size_t i = 0; i < values.size(); ++i) {
    uint16_t h = glm::packHalf1x16(values[i]);
    std::memcpy(&bytes[2 * i], &h, 2);
  }
  return bytes;
}

}  // namespace bounce
