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
               uint32_t imageCount, std::span<const uint32_t> specialization = {},
               uint64_t sampledBindings = 0)
      : ComputePass(context, scene, shader, imageCount, sizeof(gpu::RestirGiPassConstants), 1,
                    specialization, sampledBindings) {}

  // Binds the images the pass declared with bindings, pushes the constants, covers `extent`
  // with groups of groupSide^2 threads (the shader's local size).
  void record(VkCommandBuffer cmd, const graph::PassResources& resources,
              const gpu::RestirGiPassConstants& constants, VkExtent2D extent,
              uint32_t groupSide = gpu::RESTIR_GI_GROUP_SIZE) {
    bind(cmd, constants, resources);
    vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, groupSide, groupSide);
  }
  // The same for a pass that walks ray list `list` of gi.ray-lists (`rayLists`): as many groups
  // as the pass that filled the list counted (shared/restir_gi_io.h, "Ray lists").
  void recordOverRayList(VkCommandBuffer cmd, const graph::PassResources& resources,
                         const gpu::RestirGiPassConstants& constants, graph::BufferHandle rayLists,
                         uint32_t list) {
    bind(cmd, constants, resources);
    vkCmdDispatchIndirect(
        cmd, resources.buffer(rayLists).buffer,
        list * sizeof(gpu::GiRayListHeader) + offsetof(gpu::GiRayListHeader, groupsX));
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
  // gi.ray-lists, emptied at the top of the chain (declareRayLists).
  graph::BufferHandle rayLists;

  gpu::RestirGiPassConstants passConstants(bool historyValid, uint32_t variant = 0) const {
    return {in.frame.constantsAddress,
            constants,
            historyValid ? 1u : 0u,
            variant,
            historyScale,
            0u,
            0u};
  }
  // The same for the passes that fill or walk a ray list: with gi.ray-lists' address.
  gpu::RestirGiPassConstants rayListConstants(const graph::PassResources& r) const {
    gpu::RestirGiPassConstants c = passConstants(false);
    c.rayLists = r.buffer(rayLists).address;
    return c;
  }
};

// The four images of a reservoir (shared/restir_gi_io.h): sample, radiance, origin, normals.
using ReservoirImages = std::array<graph::ImageHandle, 4>;
// gi.reservoir.*: the reservoir fed back from frame to frame (gi-restir-temporal's output).
using ReservoirHistory = std::array<graph::HistoryImage, 4>;

ReservoirImages createReservoirImages(graph::FrameGraph& graph, const std::string& prefix,
                                      graph::ImageSize giSize);
ReservoirHistory createReservoirHistory(graph::FrameGraph& graph, graph::ImageSize giSize);

// gi.ray-lists (shared/restir_gi_io.h, "Ray lists"), both lists emptied by `gi-ray-lists-reset`
// before the chain's first pass: two headers, then room for one entry per GI pixel and one per
// render pixel (8 bytes per render pixel cover both at any divisor).
graph::BufferHandle declareRayLists(graph::FrameGraph& graph);

}  // namespace bounce
