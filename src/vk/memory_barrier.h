// One global memory barrier (synchronization2): the writes of srcStage/srcAccess made available
// and visible to dstStage/dstAccess. For the few places outside the frame graph (which derives
// its own barriers, graph/barrier.h) that order work by hand: uploads, readbacks, counters.
#pragma once
#include <vulkan/vulkan.h>

namespace bounce::vk {

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

}  // namespace bounce::vk
