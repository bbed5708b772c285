#include "passes/tonemap.h"

namespace bounce {

using graph::Access;

TonemapPass::TonemapPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/tonemap", gpu::TONEMAP_BINDING_COUNT) {}

DisplayImage TonemapPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                  const HdrImage& hdr) {
  DisplayImage display{graph.createImage("tonemap.display", {VK_FORMAT_R16G16B16A16_SFLOAT})};
  // The display image leaves the frame (a file, later a swapchain): kept even when no pass
  // reads it.
  graph.addPass("tonemap", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(hdr.radiance, Access::StorageRead, gpu::TONEMAP_BINDING_HDR)
      .write(display.color, Access::StorageWrite, gpu::TONEMAP_BINDING_DISPLAY)
      .sideEffects()
      .record([this, frame](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, frame.passConstants(), frame.resolution);
      });
  return display;
}

}  // namespace bounce
