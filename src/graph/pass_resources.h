// What a pass's record callback gets: the Vulkan objects behind each resource it declared, in
// the layout it declared. Asking for an undeclared resource is an error, because the graph could
// not have synchronized it.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "graph/handles.h"

namespace bounce::graph {

class FrameGraph;

struct ResolvedImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;  // 2D (2D array when it has several layers), every mip
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  uint32_t layers = 1;
  uint32_t mips = 1;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // the layout this pass sees it in
};

struct ResolvedBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  VkDeviceAddress address = 0;
  void* mapped = nullptr;  // host pointer of readback buffers
};

// An image the pass declared with a shader binding (PassBuilder::read/write with a binding).
struct BoundImage {
  uint32_t binding = kNoBinding;
  ResolvedImage image;
};

class PassResources {
 public:
  PassResources(const FrameGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}

  ResolvedImage image(ImageHandle handle) const;
  ResolvedBuffer buffer(BufferHandle handle) const;
  // False in a history's first frame and after FrameGraph::resetHistory(): ignore `previous`.
  bool historyValid(const HistoryImage& history) const;
  bool historyValid(const HistoryBuffer& history) const;

  // Every image this pass declared with a binding, in declaration order.
  std::span<const BoundImage> boundImages() const;

  const std::string& passName() const;
  VkExtent2D renderResolution() const;
  uint64_t frameIndex() const;

 private:
  const FrameGraph& graph_;
  uint32_t pass_;
};

}  // namespace bounce::graph
