#include "vk/resources.h"

#include <cstring>
#include <utility>

#include "vk/check.h"
#include "vk/memory_barrier.h"

namespace bounce::vk {

Buffer::Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
               const std::string& name)
    : context_(&context), size_(size) {
  if (size == 0) fail("buffer '{}': zero size", name);
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = size;
  ci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(context.device(), &ci, nullptr, &buffer_));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(context.device(), buffer_, &req);
  memory_ = context.allocate(req, use, true);
  VK_CHECK(vkBindBufferMemory(context.device(), buffer_, memory_, 0));
  VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  ai.buffer = buffer_;
  address_ = vkGetBufferDeviceAddress(context.device(), &ai);
  if (use != MemoryUse::DeviceOnly)
    VK_CHECK(vkMapMemory(context.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
  context.setObjectName(uint64_t(buffer_), VK_OBJECT_TYPE_BUFFER, name);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    reset();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    address_ = std::exchange(other.address_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void Buffer::reset() {
  if (!context_) return;
  if (buffer_) vkDestroyBuffer(context_->device(), buffer_, nullptr);
  context_->free(memory_);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  context_ = nullptr;
}

Buffer uploadBuffer(Context& context, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                    const std::string& name) {
  VkDeviceSize size = std::max<VkDeviceSize>(bytes.size(), 16);
  Buffer device(context, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::DeviceOnly,
                name);
  if (bytes.empty()) return device;
  Buffer staging(context, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload,
                 name + ".staging");
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  context.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), device.handle(), 1, &region);
  });
  return device;
}

void downloadBuffer(Context& context, const Buffer& buffer, std::span<std::byte> out) {
  if (out.size() > buffer.size())
    fail("download of {} bytes from a {}-byte buffer", out.size(), buffer.size());
  if (out.empty()) return;
  Buffer readback(context, out.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback,
                  "readback");
  context.submitAndWait([&](VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy region{0, 0, out.size()};
    vkCmdCopyBuffer(cmd, buffer.handle(), readback.handle(), 1, &region);
  });
  std::memcpy(out.data(), readback.mapped(), out.size());
}

Image::Image(Context& context, VkFormat format, uint32_t width, uint32_t height, uint32_t layers,
             uint32_t mips, VkImageUsageFlags usage, const std::string& name,
             std::optional<VkImageViewType> viewType)
    : context_(&context),
      format_(format),
      width_(width),
      height_(height),
      layers_(layers),
      mips_(mips) {
  if (width == 0 || height == 0 || layers == 0 || mips == 0)
    fail("image '{}': empty extent {}x{}x{} mips {}", name, width, height, layers, mips);
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {width, height, 1};
  ci.mipLevels = mips;
  ci.arrayLayers = layers;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VK_CHECK(vkCreateImage(context.device(), &ci, nullptr, &image_));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(context.device(), image_, &req);
  memory_ = context.allocate(req, MemoryUse::DeviceOnly, false);
  VK_CHECK(vkBindImageMemory(context.device(), image_, memory_, 0));

  bool depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D24_UNORM_S8_UINT;
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image_;
  vi.viewType = layers > 1 || (usage & VK_IMAGE_USAGE_SAMPLED_BIT) ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                                                   : VK_IMAGE_VIEW_TYPE_2D;
  if (viewType) vi.viewType = *viewType;
  vi.format = format;
  vi.subresourceRange = {
      VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, mips, 0,
      layers};
  VK_CHECK(vkCreateImageView(context.device(), &vi, nullptr, &view_));
  context.setObjectName(uint64_t(image_), VK_OBJECT_TYPE_IMAGE, name);
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    reset();
    context_ = std::exchange(other.context_, nullptr);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    format_ = other.format_;
    width_ = other.width_;
    height_ = other.height_;
    layers_ = other.layers_;
    mips_ = other.mips_;
  }
  return *this;
}

void Image::reset() {
  if (!context_) return;
  if (view_) vkDestroyImageView(context_->device(), view_, nullptr);
  if (image_) vkDestroyImage(context_->device(), image_, nullptr);
  context_->free(memory_);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  context_ = nullptr;
}

void uploadImage(Context& context, Image& image, std::span<const uint8_t> texels,
                 uint32_t bytesPerTexel) {
  size_t expected = 0;
  for (uint32_t m = 0; m < image.mips(); ++m)
    expected += size_t(std::max(1u, image.width() >> m)) * std::max(1u, image.height() >> m) *
                bytesPerTexel;
  expected *= image.layers();
  if (texels.size() != expected)
    fail("image upload: {} bytes given, {} expected", texels.size(), expected);
  Buffer staging(context, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload,
                 "image.staging");
  std::memcpy(staging.mapped(), texels.data(), texels.size());

  // Mip-major texels: one copy region per mip covers all layers.
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  for (uint32_t m = 0; m < image.mips(); ++m) {
    uint32_t w = std::max(1u, image.width() >> m), h = std::max(1u, image.height() >> m);
    VkBufferImageCopy r{};
    r.bufferOffset = offset;
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, image.layers()};
    r.imageExtent = {w, h, 1};
    regions.push_back(r);
    offset += VkDeviceSize(w) * h * bytesPerTexel * image.layers();
  }

  context.submitAndWait([&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier2 toTransfer{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    toTransfer.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
    toTransfer.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toTransfer.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toTransfer.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    toTransfer.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toTransfer.image = image.handle();
    toTransfer.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, image.mips(), 0, image.layers()};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &toTransfer;
    vkCmdPipelineBarrier2(cmd, &dep);
    vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()),
                           regions.data());
    VkImageMemoryBarrier2 toRead = toTransfer;
    toRead.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toRead.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toRead.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    toRead.dstAccessMask = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    toRead.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toRead.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    dep.pImageMemoryBarriers = &toRead;
    vkCmdPipelineBarrier2(cmd, &dep);
  });
}

}  // namespace bounce::vk
