// What the stages of the ReSTIR GI chain share: the pass shape and this frame's context.
#pragma once
#include <array>
#include <string>

#include "gi/diffuse_gi.h"
#include "passes/image_pass.h"
#include "shared/restir_gi_io.h"

namespace bounce {

// One compute pass of the chain: the shared ComputePass shape (scene at set 0, storage images at
// set 1 with bindings named in shared/restir_gi_io.h) with gpu::RestirGiPassConstants in push
// constants (the frame's and the chain's constants by address), one thread per pixel of
// `extent` in RESTIR_GI_GROUP_SIZE^2 groups.
class RestirGiPass : public ComputePass {
 public:
  RestirGiPass(vk::Context& context, const GpuScene& scene, const std::string& shader,
               uint32_t imageCount)
      : ComputePass(context, scene, shader, imageCount, sizeof(gpu::RestirGiPassConstants)) {}

  // Binds the images the pass declared with bindings, pushes the constants, covers `extent`.
  void record(VkCommandBuffer cmd, const graph::PassResources& resources,
              const gpu::RestirGiPassConstants& constants, VkExtent2D extent) {
    bind(cmd, constants, resources);
    vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                          gpu::RESTIR_GI_GROUP_SIZE, gpu::RESTIR_GI_GROUP_SIZE);
  }
};

// This frame's facts every stage's passes read; copied into their record callbacks.
struct RestirFrame {
  GiInputs in;
  graph::ImageSize giSize;  // GI resolution, as the graph sizes images
  VkExtent2D giResolution{};
  VkDeviceAddress constants = 0;  // gpu::RestirGiConstants
  float historyScale = 1.0f;      // RestirGiPassConstants::historyScale
  // A lighting cut: this frame drops the histories that hold light (RestirGi::lightingCut).
  bool lightCutPending = false;

  gpu::RestirGiPassConstants passConstants(bool historyValid, uint32_t variant = 0) const {
    return {
        in.frame.constantsAddress, constants, historyValid ? 1u : 0u, variant, historyScale, 0u};
  }
};

// The four images of a reservoir (shared/restir_gi_io.h): sample, radiance, origin, normals.
using ReservoirImages = std::array<graph::ImageHandle, 4>;
// gi.reservoir.*: the reservoir fed back from frame to frame (gi-restir-temporal's output).
using ReservoirHistory = std::array<graph::HistoryImage, 4>;

ReservoirImages createReservoirImages(graph::FrameGraph& graph, const std::string& prefix,
                                      graph::ImageSize giSize);
ReservoirHistory createReservoirHistory(graph::FrameGraph& graph, graph::ImageSize giSize);

}  // namespace bounce
