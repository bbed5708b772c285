#include "passes/composite.h"

#include "lighting/specular_albedo.h"

namespace bounce {

using graph::Access;

// The read-only inputs are sampled images (docs/architecture.md, "Sampled inputs").
CompositePass::CompositePass(vk::Context& context, const GpuScene& scene,
                             const SpecularAlbedoTable& specularAlbedo)
    : specularAlbedo_(specularAlbedo),
      pass_(context, scene, "passes/composite", gpu::COMPOSITE_BINDING_COUNT,
            sizeof(gpu::CompositeConstants), 1, {},
            bindingMask({gpu::COMPOSITE_BINDING_BASE_COLOR, gpu::COMPOSITE_BINDING_NORMALS,
                         gpu::COMPOSITE_BINDING_DEPTH, gpu::COMPOSITE_BINDING_EMISSIVE,
                         gpu::COMPOSITE_BINDING_FLAGS, gpu::COMPOSITE_BINDING_SHADOWS,
                         gpu::COMPOSITE_BINDING_SKY, gpu::COMPOSITE_BINDING_GI_DIFFUSE,
                         gpu::COMPOSITE_BINDING_REFLECTIONS, gpu::COMPOSITE_BINDING_DIRECT})) {}

HdrImage CompositePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                const GBuffer& gbuffer, const Shadows& shadows,
                                const DirectLightImage& direct, const SkyImage& sky,
                                const IndirectLight& indirect) {
  HdrImage hdr{graph.createImage("composite.hdr", {VK_FORMAT_R16G16B16A16_SFLOAT})};
  graph.addPass("composite", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(gbuffer.baseColor, Access::SampledRead, gpu::COMPOSITE_BINDING_BASE_COLOR)
      .read(gbuffer.normals, Access::SampledRead, gpu::COMPOSITE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::SampledRead, gpu::COMPOSITE_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::SampledRead, gpu::COMPOSITE_BINDING_EMISSIVE)
      .read(gbuffer.flags, Access::SampledRead, gpu::COMPOSITE_BINDING_FLAGS)
      .read(shadows.visibility, Access::SampledRead, gpu::COMPOSITE_BINDING_SHADOWS)
      .read(sky.radiance, Access::SampledRead, gpu::COMPOSITE_BINDING_SKY)
      .read(indirect.diffuse, Access::SampledRead, gpu::COMPOSITE_BINDING_GI_DIFFUSE)
      .read(indirect.reflections, Access::SampledRead, gpu::COMPOSITE_BINDING_REFLECTIONS)
      .read(direct.radiance, Access::SampledRead, gpu::COMPOSITE_BINDING_DIRECT)
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
