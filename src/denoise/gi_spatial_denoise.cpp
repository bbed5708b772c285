#include "denoise/gi_spatial_denoise.h"

namespace bounce {

using gpu::GI_SPATIAL_DENOISE_COLUMNS;
using gpu::GI_SPATIAL_DENOISE_ROWS;
using graph::Access;

GiSpatialDenoise::GiSpatialDenoise(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "denoise/gi_spatial_denoise", gpu::GI_SPATIAL_DENOISE_BINDING_COUNT,
            sizeof(gpu::RestirGiPassConstants), 2) {}

void GiSpatialDenoise::declare(graph::FrameGraph& graph, const FrameContext& frame,
                               const GBuffer& gbuffer, const GiSpatialDenoiseInputs& in,
                               graph::ImageHandle output) {
  // Two passes of one shader: across the rows into gi.spatial-denoise-rows
  // (gi-spatial-denoise-rows), then down the columns into `output` (gi-spatial-denoise). The
  // shader's header says why the blur is separable.
  const graph::ImageHandle rows =
      graph.createImage("gi.spatial-denoise-rows", {VK_FORMAT_R16G16B16A16_SFLOAT});
  declareDirection(graph, frame, gbuffer, in, in.noisy, rows, GI_SPATIAL_DENOISE_ROWS,
                   "gi-spatial-denoise-rows");
  declareDirection(graph, frame, gbuffer, in, rows, output, GI_SPATIAL_DENOISE_COLUMNS,
                   "gi-spatial-denoise");
}

void GiSpatialDenoise::declareDirection(graph::FrameGraph& graph, const FrameContext& frame,
                                        const GBuffer& gbuffer, const GiSpatialDenoiseInputs& in,
                                        graph::ImageHandle input, graph::ImageHandle output,
                                        uint32_t direction, const char* name) {
  graph::PassBuilder pass = graph.addPass(name, graph::QueueKind::Compute);
  pass.write(output, Access::StorageWrite, gpu::GI_SPATIAL_DENOISE_BINDING_OUTPUT)
      .read(frame.constants, Access::StorageRead)
      .read(input, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_INPUT)
      .read(gbuffer.normals, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_DEPTH)
      .read(gbuffer.flags, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_FLAGS);
  if (in.occlusion)
    pass.read(*in.occlusion, Access::StorageRead, gpu::GI_SPATIAL_DENOISE_BINDING_OCCLUSION);
  else
    pass.readPlaceholder(gbuffer.flags, gpu::GI_SPATIAL_DENOISE_BINDING_OCCLUSION);
  gpu::RestirGiPassConstants constants = in.constants;
  constants.variant = direction;
  pass.record([this, frame, constants](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass_.bind(cmd, constants, r, constants.variant);
    vk::ComputePipeline::dispatchCovering(cmd, frame.resolution.width, frame.resolution.height,
                                          gpu::RESTIR_GI_GROUP_SIZE, gpu::RESTIR_GI_GROUP_SIZE);
  });
}

}  // namespace bounce
