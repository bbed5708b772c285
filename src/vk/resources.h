// GPU buffers and images owned by RAII handles. Resources are created at initialisation (and on
// resize), never per frame (DESIGN.md §1). Buffers always have a device address: shaders reach
// scene-sized data through buffer_reference pointers.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace bounce::vk {

class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
         const std::string& name);
  ~Buffer() { reset(); }
  Buffer(Buffer&& other) noexcept { *this = std::move(other); }
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  // Host pointer for Upload/Readback buffers (and DeviceOnly ones on unified-memory devices
  // never: use upload()); null otherwise.
  void* mapped() const { return mapped_; }
  template <typename T>
  T* mappedAs() const {
    return static_cast<T*>(mapped_);
  }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
  void reset();

 private:
  Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;
};

// A device-only buffer filled with `bytes` through a staging copy. Zero-sized data gets a
// 16-byte buffer so every address is valid.
Buffer uploadBuffer(Context& context, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                    const std::string& name);

template <typename T>
Buffer uploadVector(Context& context, std::span<const T> items, VkBufferUsageFlags usage,
                    const std::string& name) {
  return uploadBuffer(context, std::as_bytes(items), usage, name);
}

// Copies a device buffer's contents back to the host (through a readback buffer).
void downloadBuffer(Context& context, const Buffer& buffer, std::span<std::byte> out);

class Image {
 public:
  Image() = default;
  // A 2D (array) image with a full view over its layers and mips. The view is a 2D array when
  // the image has several layers or is sampled (scene textures), unless `viewType` says otherwise
  // (storage images bound as image2D need a 2D view).
  Image(Context& context, VkFormat format, uint32_t width, uint32_t height, uint32_t layers,
        uint32_t mips, VkImageUsageFlags usage, const std::string& name,
        std::optional<VkImageViewType> viewType = std::nullopt);
  ~Image() { reset(); }
  Image(Image&& other) noexcept { *this = std::move(other); }
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return format_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t layers() const { return layers_; }
  uint32_t mips() const { return mips_; }
  void reset();

 private:
  Context* context_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  uint32_t width_ = 0, height_ = 0, layers_ = 0, mips_ = 0;
};

// Fills every layer and mip of a sampled image from tightly packed texels (mip-major: every
// layer of mip 0, then every layer of mip 1, ...; rows top to bottom) and leaves it in
// SHADER_READ_ONLY_OPTIMAL.
void uploadImage(Context& context, Image& image, std::span<const uint8_t> texels,
                 uint32_t bytesPerTexel);

}  // namespace bounce::vk
