#include "passes/composite.h"

namespace bounce {

using graph::Access;

CompositePass::CompositePass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/composite", gpu::COMPOSITE_BINDING_COUNT) {}

HdrImage CompositePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                const GBuffer& gbuffer, const Shadows& shadows, const SkyImage& sky,
                                const IndirectLight& indirect) {
  HdrImage hdr{graph.createImage("composite.hdr", {VK_FORMAT_R16G16B16A16_SFLOAT})};
  graph.addPass("composite", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(gbuffer.baseColor, Access::StorageRead, gpu::COMPOSITE_BINDING_BASE_COLOR)
      .read(gbuffer.normals, Access::StorageRead, gpu::COMPOSITE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::COMPOSITE_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::StorageRead, gpu::COMPOSITE_BINDING_EMISSIVE)
      .read(gbuffer.flags, Access::StorageRead, gpu::COMPOSITE_BINDING_FLAGS)
      .read(shadows.visibility, Access::StorageRead, gpu::COMPOSITE_BINDING_SHADOWS)
      .read(sky.radiance, Access::StorageRead, gpu::COMPOSITE_BINDING_SKY)
      .read(indirect.diffuse, Access::StorageRead, gpu::COMPOSITE_BINDING_GI_DIFFUSE)
      .read(indirect.reflections, Access::StorageRead, gpu::COMPOSITE_BINDING_REFLECTIONS)
      .write(hdr.radiance, Access::StorageWrite, gpu::COMPOSITE_BINDING_OUTPUT)
      .record([this, frame](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, frame.passConstants(), frame.resolution);
      });
  return hdr;
}

}  // namespace bounce
