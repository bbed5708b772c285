#include "denoise/gi_spatial_denoise.h"

namespace bounce {

using graph::Access;

GiSpatialDenoise::GiSpatialDenoise(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "denoise/gi_spatial_denoise", gpu::GI_SPATIAL_DENOISE_BINDING_COUNT,
            sizeof(gpu::RestirGiPassConstants)) {}

void GiSpatialDenoise::declare(graph::FrameGraph& graph, const FrameContext& frame,
                               const GBuffer& gbuffer, const GiSpatialDenoiseInputs& in,
                               graph::ImageHandle output) {
  graph::PassBuilder pass = graph.addPass("gi-spatial-denoise", graph::QueueKind::Compute);
  pass.write(output, Access::StorageWrite, gpu::GI_SPATIAL_DENOISE_BINDING_OUTPUT)
      .read(frame.constants, Access::StorageRead)
      .read(in.noisy, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_INPUT)
      .read(gbuffer.normals, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_DEPTH)
      .read(gbuffer.flags, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_FLAGS);
  if (in.occlusion)
    pass.read(*in.occlusion, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_OCCLUSION);
  else
    pass.readPlaceholder(gbuffer.flags, gpu::GI_SPATIAL_DENOISE_BINDING_OCCLUSION);
  const gpu::RestirGiPassConstants constants = in.constants;
  pass.record([this, frame, constants](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass_.bind(cmd, constants, r);
    vk::ComputePipeline::dispatchCovering(cmd, frame.resolution.width, frame.resolution.height,
                                          gpu::RESTIR_GI_GROUP_SIZE, gpu::RESTIR_GI_GROUP_SIZE);
  });
}

}  // namespace bounce
