#include "passes/tonemap.h"

namespace bounce {

using graph::Access;

TonemapPass::TonemapPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/tonemap", gpu::TONEMAP_BINDING_COUNT,
            sizeof(gpu::TonemapConstants)) {}

DisplayImage TonemapPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                  const HdrImage& hdr, const std::optional<Exposure>& exposure) {
  DisplayImage display{graph.createImage("tonemap.display", {VK_FORMAT_R16G16B16A16_SFLOAT})};
  // The display image leaves the frame (a file, later a swapchain): kept even when no pass
  // reads it.
  graph::PassBuilder pass = graph.addPass("tonemap", graph::QueueKind::Compute);
  pass.read(frame.constants, Access::StorageRead)
      .read(hdr.radiance, Access::StorageRead, gpu::TONEMAP_BINDING_HDR)
      .write(display.color, Access::StorageWrite, gpu::TONEMAP_BINDING_DISPLAY)
      .sideEffects();
  if (exposure) pass.read(exposure->state, Access::StorageRead);
  pass.record([this, frame, exposure](VkCommandBuffer cmd, const graph::PassResources& r) {
    gpu::TonemapConstants constants{frame.constantsAddress, 0};
    if (exposure) constants.exposureState = r.buffer(exposure->state).address;
    pass_.bind(cmd, constants, r);
    vk::ComputePipeline::dispatchCovering(cmd, frame.resolution.width, frame.resolution.height,
                                          gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
  });
  return display;
}

}  // namespace bounce
