// The compiled plan as text, for `--graph`-style dumps and test failure messages.
#include <utility>

#include <fmt/format.h>

#include "graph/frame_graph.h"

namespace bounce::graph {

namespace {

const char* layoutName(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED:
      return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL:
      return "GENERAL";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
      return "COLOR_ATTACHMENT";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL:
      return "DEPTH_ATTACHMENT";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
      return "DEPTH_READ_ONLY";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
      return "SHADER_READ_ONLY";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL:
      return "TRANSFER_SRC";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL:
      return "TRANSFER_DST";
    default:
      return "other";
  }
}

template <typename Flags>
std::string flagNames(Flags flags, std::initializer_list<std::pair<Flags, const char*>> names) {
  if (flags == 0) return "NONE";
  std::string text;
  for (auto [bit, name] : names)
    if ((flags & bit) == bit) {
      if (!text.empty()) text += '|';
      text += name;
      flags &= ~bit;
    }
  if (flags) text += fmt::format("{}{:#x}", text.empty() ? "" : "|", uint64_t(flags));
  return text;
}

std::string stageNames(VkPipelineStageFlags2 stages) {
  return flagNames<VkPipelineStageFlags2>(
      stages, {{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "COMPUTE"},
               {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, "VERTEX"},
               {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "FRAGMENT"},
               {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "COLOR_OUTPUT"},
               {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "EARLY_TESTS"},
               {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "LATE_TESTS"},
               {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, "TRANSFER"},
               {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, "INDIRECT"},
               {VK_PIPELINE_STAGE_2_HOST_BIT, "HOST"}});
}

std::string accessNames(VkAccessFlags2 access) {
  return flagNames<VkAccessFlags2>(access,
                                   {{VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "SAMPLED_READ"},
                                    {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "STORAGE_READ"},
                                    {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "STORAGE_WRITE"},
                                    {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "COLOR_READ"},
                                    {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "COLOR_WRITE"},
                                    {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "DEPTH_READ"},
                                    {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "DEPTH_WRITE"},
                                    {VK_ACCESS_2_TRANSFER_READ_BIT, "TRANSFER_READ"},
                                    {VK_ACCESS_2_TRANSFER_WRITE_BIT, "TRANSFER_WRITE"},
                                    {VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, "INDIRECT_READ"},
                                    {VK_ACCESS_2_HOST_READ_BIT, "HOST_READ"}});
}

std::string describeBarrier(const PlannedBarrier& planned) {
  const Barrier& b = planned.barrier;
  std::string text =
      fmt::format("    {}: {}/{} -> {}/{}", planned.resourceName, stageNames(b.srcStages),
                  accessNames(b.srcAccess), stageNames(b.dstStages), accessNames(b.dstAccess));
  if (planned.isImage)
    text += fmt::format(", {} -> {}", layoutName(b.oldLayout), layoutName(b.newLayout));
  return text + "\n";
}

}  // namespace

std::string FrameGraph::describe() const {
  std::string text = fmt::format("frame {}\n", frameIndex_);
  for (const PassPlan& pass : plan_.passes) {
    text += fmt::format("  {} ({})\n", pass.name, queueKindName(pass.kind));
    for (const PlannedBarrier& barrier : pass.barriers) text += describeBarrier(barrier);
  }
  if (!plan_.finalBarriers.empty()) text += "  end of frame\n";
  for (const PlannedBarrier& barrier : plan_.finalBarriers) text += describeBarrier(barrier);
  for (const std::string& culled : plan_.culledPasses)
    text += fmt::format("  culled: {}\n", culled);
  return text;
}

// ---- plan lookups ---------------------------------------------------------------------------

const PlannedBarrier* PassPlan::barrierFor(const std::string& resource) const {
  for (const PlannedBarrier& b : barriers)
    if (b.resourceName == resource) return &b;
  return nullptr;
}

const PassPlan* FramePlan::pass(const std::string& name) const {
  for (const PassPlan& p : passes)
    if (p.name == name) return &p;
  return nullptr;
}

bool FramePlan::culled(const std::string& name) const {
  for (const std::string& c : culledPasses)
    if (c == name) return true;
  return false;
}

}  // namespace bounce::graph
