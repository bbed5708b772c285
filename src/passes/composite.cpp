#include "passes/composite.h"

#include "lighting/specular_albedo.h"

namespace bounce {

using graph::Access;

CompositePass::CompositePass(vk::Context& context, const GpuScene& scene,
                             const SpecularAlbedoTable& specularAlbedo)
    : specularAlbedo_(specularAlbedo),
      pass_(context, scene, "passes/composite", gpu::COMPOSITE_BINDING_COUNT,
            sizeof(gpu::CompositeConstants)) {}

HdrImage CompositePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                const GBuffer& gbuffer, const Shadows& shadows,
                                const DirectLightImage& direct, const SkyImage& sky,
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
      .read(direct.radiance, Access::StorageRead, gpu::COMPOSITE_BINDING_DIRECT)
      .write(hdr.radiance, Access::StorageWrite, gpu::COMPOSITE_BINDING_OUTPUT)
      .record([this, frame, indirect](VkCommandBuffer cmd, const graph::PassResources& r) {
        const gpu::CompositeConstants push{frame.constantsAddress, specularAlbedo_.address(),
                                           indirect.reflectionMaxRoughness, 0u};
        pass_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, frame.resolution.width, frame.resolution.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  return hdr;
}

}  // namespace bounce
