#include "passes/sky.h"

namespace bounce {

using graph::Access;

SkyPass::SkyPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/sky", gpu::SKY_BINDING_COUNT) {}

SkyImage SkyPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                          const GBuffer& gbuffer) {
  SkyImage sky{graph.createImage("sky.radiance", {VK_FORMAT_R16G16B16A16_SFLOAT})};
  graph.addPass("sky", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(gbuffer.flags, Access::StorageRead, gpu::SKY_BINDING_FLAGS)
      .write(sky.radiance, Access::StorageWrite, gpu::SKY_BINDING_RADIANCE)
      .record([this, frame](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, frame.passConstants(), frame.resolution);
      });
  return sky;
}

}  // namespace bounce
