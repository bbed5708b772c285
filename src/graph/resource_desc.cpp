#include "graph/resource_desc.h"

#include "core/error.h"

namespace bounce::graph {

namespace {

uint32_t divideRoundingUp(uint32_t value, uint32_t divisor) {
  return (value + divisor - 1) / divisor;
}

}  // namespace

const char* resourceKindName(ResourceKind kind) {
  switch (kind) {
    case ResourceKind::Transient:
      return "transient";
    case ResourceKind::Persistent:
      return "persistent";
    case ResourceKind::History:
      return "history";
    case ResourceKind::Imported:
      return "imported";
  }
  return "?";
}

VkExtent2D ImageSize::resolve(VkExtent2D renderResolution) const {
  if (!followsResolution()) return {width, height};
  return {divideRoundingUp(renderResolution.width, divisor),
          divideRoundingUp(renderResolution.height, divisor)};
}

VkDeviceSize BufferSize::resolve(VkExtent2D renderResolution) const {
  if (!followsResolution()) return bytes;
  return bytes + VkDeviceSize(divideRoundingUp(renderResolution.width, divisor)) *
                     divideRoundingUp(renderResolution.height, divisor) * bytesPerPixel;
}

void checkImageDesc(const std::string& name, const ImageDesc& desc) {
  if (desc.format == VK_FORMAT_UNDEFINED) fail("image '{}': no format", name);
  if (!desc.size.followsResolution() && (desc.size.width == 0 || desc.size.height == 0))
    fail("image '{}': empty extent {}x{}", name, desc.size.width, desc.size.height);
  if (desc.layers == 0 || desc.mips == 0)
    fail("image '{}': {} layers and {} mips (each must be at least 1)", name, desc.layers,
         desc.mips);
}

void checkBufferDesc(const std::string& name, const BufferDesc& desc) {
  if (desc.size.bytes == 0 && desc.size.bytesPerPixel == 0) fail("buffer '{}': zero size", name);
  if (desc.size.divisor == 0) fail("buffer '{}': resolution divisor 0", name);
  if (desc.memory == vk::MemoryUse::Upload)
    fail("buffer '{}': upload buffers are written by the host; import them instead", name);
}

bool isDepthFormat(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return true;
    default:
      return false;
  }
}

VkImageAspectFlags aspectsOf(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
      return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
      return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

uint32_t bytesPerTexel(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT:
      return 1;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_UINT:
    case VK_FORMAT_R8G8_UNORM:
      return 2;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
    case VK_FORMAT_D32_SFLOAT:
      return 4;
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_UNORM:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT:
      return 16;
    default:
      return 0;
  }
}

}  // namespace bounce::graph
