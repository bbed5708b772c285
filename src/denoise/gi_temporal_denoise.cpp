#include "denoise/gi_temporal_denoise.h"

namespace bounce {

using graph::Access;

// The read-only inputs it reads around each pixel are sampled images (docs/architecture.md,
// "Sampled inputs").
GiTemporalDenoise::GiTemporalDenoise(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "denoise/gi_temporal_denoise", gpu::GI_DENOISE_BINDING_COUNT,
            sizeof(gpu::RestirGiPassConstants), 1, {},
            bindingMask({gpu::GI_DENOISE_BINDING_INPUT, gpu::GI_DENOISE_BINDING_PREVIOUS,
                         gpu::GI_DENOISE_BINDING_PREVIOUS_FAST})) {}

void GiTemporalDenoise::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                const GBuffer& gbuffer, const GiTemporalDenoiseInputs& in,
                                graph::ImageHandle output) {
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  graph::HistoryImage slow = graph.createHistoryImage("gi.denoised", {rgba16f});
  graph::HistoryImage fast = graph.createHistoryImage("gi.denoised-fast", {rgba16f});
  const graph::HistoryImage depth = gbuffer.depth;
  graph::PassBuilder pass = graph.addPass("gi-temporal-denoise", graph::QueueKind::Compute);
  pass.read(frame.constants, Access::StorageRead)
      .write(output, Access::StorageWrite, gpu::GI_DENOISE_BINDING_OUTPUT)
      .read(in.noisy, Access::SampledRead, gpu::GI_DENOISE_BINDING_INPUT)
      .read(gbuffer.normals, Access::StorageRead, gpu::GI_DENOISE_BINDING_NORMALS)
      .read(depth.current, Access::StorageRead, gpu::GI_DENOISE_BINDING_DEPTH)
      .read(depth.previous, Access::StorageRead, gpu::GI_DENOISE_BINDING_PREVIOUS_DEPTH)
      .read(gbuffer.flags, Access::StorageRead, gpu::GI_DENOISE_BINDING_FLAGS)
      .read(gbuffer.velocity, Access::StorageRead, gpu::GI_DENOISE_BINDING_VELOCITY)
      .read(slow.previous, Access::SampledRead, gpu::GI_DENOISE_BINDING_PREVIOUS)
      .read(fast.previous, Access::SampledRead, gpu::GI_DENOISE_BINDING_PREVIOUS_FAST)
      .read(in.validity, Access::StorageRead, gpu::GI_DENOISE_BINDING_VALIDITY);
  if (in.occlusionValidity)
    pass.read(*in.occlusionValidity, Access::StorageRead,
              gpu::GI_DENOISE_BINDING_OCCLUSION_VALIDITY);
  else
    pass.readPlaceholder(in.placeholderR16f, gpu::GI_DENOISE_BINDING_OCCLUSION_VALIDITY);
  pass.write(slow.current, Access::StorageWrite, gpu::GI_DENOISE_BINDING_CURRENT)
      .write(fast.current, Access::StorageWrite, gpu::GI_DENOISE_BINDING_CURRENT_FAST)
      .record([this, frame, in, slow, fast, depth](VkCommandBuffer cmd,
                                                   const graph::PassResources& r) {
        gpu::RestirGiPassConstants constants = in.constants;
        constants.historyValid = !in.dropHistory && r.historyValid(slow) && r.historyValid(fast) &&
                                 r.historyValid(depth);
        pass_.bind(cmd, constants, r);
        vk::ComputePipeline::dispatchCovering(cmd, frame.resolution.width, frame.resolution.height,
                                              gpu::RESTIR_GI_GROUP_SIZE, gpu::RESTIR_GI_GROUP_SIZE);
      });
}

}  // namespace bounce
