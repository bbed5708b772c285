// What a frame-graph resource is: its lifetime kind and its size, format and memory. Sizes may
// follow the render resolution (full, half, quarter) so that a resize recreates them; usage flags
// are not part of a description, they follow from how passes access the resource.
#pragma once
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace bounce::graph {

enum class ResourceKind {
  Transient,   // lives one frame: contents are undefined at the start of each frame
  Persistent,  // lives across frames (a cache); zeroed when (re)created
  History,     // a ping-pong pair: `current` is written this frame, `previous` is last frame's
  Imported,    // owned outside the graph (scene buffers, an output image)
};
const char* resourceKindName(ResourceKind kind);

// A fixed extent, or the render resolution divided by `divisor` (rounded up, so a half-res
// image covers every full-res pixel).
struct ImageSize {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t divisor = 1;  // 0 for a fixed extent

  static ImageSize fixed(uint32_t width, uint32_t height) { return {width, height, 0}; }
  static ImageSize dividedRes(uint32_t divisor) { return {0, 0, divisor}; }
  static ImageSize fullRes() { return dividedRes(1); }
  static ImageSize halfRes() { return dividedRes(2); }
  static ImageSize quarterRes() { return dividedRes(4); }

  bool followsResolution() const { return divisor != 0; }
  VkExtent2D resolve(VkExtent2D renderResolution) const;
  bool operator==(const ImageSize&) const = default;
};

struct ImageDesc {
  VkFormat format = VK_FORMAT_UNDEFINED;
  ImageSize size = ImageSize::fullRes();
  uint32_t layers = 1;
  uint32_t mips = 1;
  bool operator==(const ImageDesc&) const = default;
};

// A fixed byte count, or bytes per pixel of the render resolution divided by `divisor` (for
// per-pixel data such as reservoirs, which must follow a resize), plus `bytes` of header then.
struct BufferSize {
  VkDeviceSize bytes = 0;
  VkDeviceSize bytesPerPixel = 0;
  uint32_t divisor = 1;

  static BufferSize fixed(VkDeviceSize bytes) { return {bytes, 0, 1}; }
  static BufferSize perPixel(VkDeviceSize bytesPerPixel, uint32_t divisor = 1) {
    return {0, bytesPerPixel, divisor};
  }

  // The same plus `headerBytes` in front (counters before per-pixel entries).
  BufferSize withHeader(VkDeviceSize headerBytes) const {
    BufferSize s = *this;
    s.bytes = headerBytes;
    return s;
  }

  bool followsResolution() const { return bytesPerPixel != 0; }
  VkDeviceSize resolve(VkExtent2D renderResolution) const;
  bool operator==(const BufferSize&) const = default;
};

struct BufferDesc {
  BufferSize size;
  // Readback buffers are mapped; whatever a frame writes to one is made visible to the host at
  // the end of the frame.
  vk::MemoryUse memory = vk::MemoryUse::DeviceOnly;
  bool operator==(const BufferDesc&) const = default;
};

// Throws bounce::Error naming `name` when a description cannot be created (no format, empty).
void checkImageDesc(const std::string& name, const ImageDesc& desc);
void checkBufferDesc(const std::string& name, const BufferDesc& desc);

bool isDepthFormat(VkFormat format);
VkImageAspectFlags aspectsOf(VkFormat format);
// Bytes per texel of the formats the renderer uses; 0 for others (debug views reject those).
uint32_t bytesPerTexel(VkFormat format);

}  // namespace bounce::graph
