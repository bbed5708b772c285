#include "gi/evolve/restir/restir_gi_pass.h"

namespace bounce {

namespace {

constexpr const char* kReservoirParts[4] = {"sample", "radiance", "origin", "normals"};
constexpr VkFormat kReservoirFormats[4] = {
    VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT,
    VK_FORMAT_R16G16B16A16_SFLOAT};

}  // namespace

ReservoirImages createReservoirImages(graph::FrameGraph& graph, const std::string& prefix,
                                      graph::ImageSize giSize) {
  ReservoirImages images;
  for (int i = 0; i < 4; ++i)
    images[i] = graph.createImage(prefix + kReservoirParts[i], {kReservoirFormats[i], giSize});
  return images;
}

ReservoirHistory createReservoirHistory(graph::FrameGraph& graph, graph::ImageSize giSize) {
  ReservoirHistory history;
  for (int i = 0; i < 4; ++i)
    history[i] = graph.createHistoryImage(std::string("gi.reservoir.") + kReservoirParts[i],
                                          {kReservoirFormats[i], giSize});
  return history;
}

graph::BufferHandle declareRayLists(graph::FrameGraph& graph) {
  graph::BufferHandle lists = graph.createBuffer(
      "gi.ray-lists", {graph::BufferSize::perPixel(8).withHeader(gpu::GI_RAY_LISTS_HEADER_BYTES)});
  graph.addPass("gi-ray-lists-reset", graph::QueueKind::Compute)
      .write(lists, graph::Access::TransferDst)
      .record([lists](VkCommandBuffer cmd, const graph::PassResources& r) {
        // No entries, and a dispatch of 0 x 1 x 1 groups until the first entry adds one.
        const gpu::GiRayListHeader empty{0u, 0u, 1u, 1u};
        const gpu::GiRayListHeader headers[2] = {empty, empty};
        vkCmdUpdateBuffer(cmd, r.buffer(lists).buffer, 0, sizeof(headers), headers);
      });
  return lists;
}

}  // namespace bounce
