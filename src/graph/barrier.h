// Barrier derivation for one resource: given what the GPU last did to it and what the next pass
// does, which synchronization2 barrier (if any) must come first. Pure CPU logic, unit-tested
// without a GPU (tests/test_frame_graph.cpp).
//
// The rules: a write, or any layout change, must wait for every earlier read and write (WAR:
// an execution dependency; WAW: also make the earlier write available). A read must see the last
// write, unless an earlier barrier already made it visible to that stage and access; reads after
// reads need nothing while the layout stays the same.
#pragma once
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "graph/access.h"

namespace bounce::graph {

struct StageAccess {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// What the GPU has done to one resource so far, as far as synchronization is concerned.
struct ResourceState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
  // Stages of the last write, plus those of later layout transitions (later barriers chain
  // through them).
  VkPipelineStageFlags2 writeStages = VK_PIPELINE_STAGE_2_NONE;
  // Write bits of the last write while it has not been made available by a barrier.
  VkAccessFlags2 pendingWrites = VK_ACCESS_2_NONE;
  // Stages that read since the last write (a later write must wait for them).
  VkPipelineStageFlags2 readStages = VK_PIPELINE_STAGE_2_NONE;
  // Stage/access pairs the last write has been made visible to.
  std::vector<StageAccess> visibleTo;
};

struct Barrier {
  VkPipelineStageFlags2 srcStages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 srcAccess = VK_ACCESS_2_NONE;
  VkPipelineStageFlags2 dstStages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 dstAccess = VK_ACCESS_2_NONE;
  VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
  VkImageLayout newLayout = VK_IMAGE_LAYOUT_UNDEFINED;
};

// Records `next` into `state` and returns the barrier that must precede it, if one is needed.
std::optional<Barrier> deriveBarrier(ResourceState& state, const AccessInfo& next, bool isImage);

}  // namespace bounce::graph
