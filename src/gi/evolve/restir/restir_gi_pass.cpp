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

}  // namespace bounce
