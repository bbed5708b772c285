#include "passes/reflections_upsample.h"

namespace bounce {

using graph::Access;

ReflectionsUpsamplePass::ReflectionsUpsamplePass(vk::Context& context, const GpuScene& gpuScene)
    : pass_(context, gpuScene, "passes/reflections_upsample",
            gpu::REFLECTIONS_UPSAMPLE_BINDING_COUNT, sizeof(gpu::ReflectionPassConstants)) {}

Reflections ReflectionsUpsamplePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                             const GBuffer& gbuffer,
                                             const TracedReflections& traced,
                                             const gpu::ReflectionPassConstants& constants) {
  Reflections out{graph.createImage("reflections", {VK_FORMAT_R16G16B16A16_SFLOAT})};
  const VkExtent2D extent = frame.resolution;
  graph.addPass("reflections-upsample", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(traced.traced, Access::StorageRead, gpu::REFLECTIONS_UPSAMPLE_BINDING_TRACED)
      .read(gbuffer.normals, Access::StorageRead, gpu::REFLECTIONS_UPSAMPLE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::REFLECTIONS_UPSAMPLE_BINDING_DEPTH)
      .read(gbuffer.flags, Access::StorageRead, gpu::REFLECTIONS_UPSAMPLE_BINDING_FLAGS)
      .write(out.radiance, Access::StorageWrite, gpu::REFLECTIONS_UPSAMPLE_BINDING_OUTPUT)
      .record([this, constants, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.bind(cmd, constants, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  return out;
}

}  // namespace bounce
