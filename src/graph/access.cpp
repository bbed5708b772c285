#include "graph/access.h"

#include <array>

namespace bounce::graph {

namespace {

// Stage value meaning "the shader stages of the pass's queue kind".
constexpr VkPipelineStageFlags2 kPassShaders = VK_PIPELINE_STAGE_2_NONE;

struct AccessRow {
  Access access;
  const char* name;
  VkPipelineStageFlags2 stages;
  VkAccessFlags2 bits;
  VkImageLayout layout;
  bool writes;
  bool keepsContents;
  bool onImages;
  bool onBuffers;
};

constexpr VkPipelineStageFlags2 kDepthTests =
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;

// Attachment accesses include their read bits: LOAD ops, blending and depth tests read.
// Depth uses the combined depth/stencil layouts, which are valid for depth-only formats and need
// no separateDepthStencilLayouts feature.
constexpr std::array<AccessRow, 11> kAccessTable = {{
    {Access::SampledRead, "SampledRead", kPassShaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, true, true, false},
    {Access::StorageRead, "StorageRead", kPassShaders, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
     VK_IMAGE_LAYOUT_GENERAL, false, true, true, true},
    {Access::StorageWrite, "StorageWrite", kPassShaders, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
     VK_IMAGE_LAYOUT_GENERAL, true, false, true, true},
    {Access::StorageReadWrite, "StorageReadWrite", kPassShaders,
     VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
     VK_IMAGE_LAYOUT_GENERAL, true, true, true, true},
    {Access::ColorAttachmentWrite, "ColorAttachmentWrite",
     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
     VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true, true, true, false},
    {Access::DepthAttachmentRead, "DepthAttachmentRead", kDepthTests,
     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
     false, true, true, false},
    {Access::DepthAttachmentWrite, "DepthAttachmentWrite", kDepthTests,
     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
     VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, true, true, true, false},
    {Access::TransferSrc, "TransferSrc", VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
     VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false, true, true, true},
    {Access::TransferDst, "TransferDst", VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true, false, true, true},
    {Access::IndirectRead, "IndirectRead", VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
     VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED, false, true, false, true},
    {Access::HostRead, "HostRead", VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
     VK_IMAGE_LAYOUT_UNDEFINED, false, true, false, true},
}};

// row() indexes the table by enum value, so the rows must stay in enum order.
constexpr bool tableInEnumOrder() {
  for (size_t i = 0; i < kAccessTable.size(); ++i)
    if (kAccessTable[i].access != Access(i)) return false;
  return true;
}
static_assert(tableInEnumOrder(), "kAccessTable rows must follow the order of enum Access");

const AccessRow& row(Access access) {
  return kAccessTable[size_t(access)];
}

VkPipelineStageFlags2 shaderStages(QueueKind kind) {
  return kind == QueueKind::Compute
             ? VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT
             : VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
}

}  // namespace

AccessInfo accessInfo(Access access, QueueKind kind) {
  const AccessRow& r = row(access);
  AccessInfo info;
  info.stages = r.stages == kPassShaders ? shaderStages(kind) : r.stages;
  info.access = r.bits;
  info.layout = r.layout;
  info.writes = r.writes;
  info.keepsContents = r.keepsContents;
  info.onImages = r.onImages;
  info.onBuffers = r.onBuffers;
  return info;
}

const char* accessName(Access access) {
  return row(access).name;
}

const char* queueKindName(QueueKind kind) {
  return kind == QueueKind::Compute ? "compute" : "graphics";
}

VkAccessFlags2 writeAccessBits(VkAccessFlags2 access) {
  constexpr VkAccessFlags2 kWrites =
      VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
      VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  return access & kWrites;
}

VkImageUsageFlags imageUsageFor(Access access) {
  switch (access) {
    case Access::SampledRead:
      return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite:
      return VK_IMAGE_USAGE_STORAGE_BIT;
    case Access::ColorAttachmentWrite:
      return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    case Access::DepthAttachmentRead:
    case Access::DepthAttachmentWrite:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    case Access::TransferSrc:
      return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferDst:
      return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    default:
      return 0;
  }
}

VkBufferUsageFlags bufferUsageFor(Access access) {
  switch (access) {
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite:
      return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    case Access::IndirectRead:
      return VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    case Access::TransferSrc:
      return VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferDst:
      return VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    default:
      return 0;
  }
}

}  // namespace bounce::graph
