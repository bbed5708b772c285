#include "passes/shadows_denoise.h"

namespace bounce {

using graph::Access;

// The read-only inputs are sampled images (docs/architecture.md, "Sampled inputs").
ShadowsDenoisePass::ShadowsDenoisePass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/shadows_denoise", gpu::SHADOWS_DENOISE_BINDING_COUNT,
            bindingMask({gpu::SHADOWS_DENOISE_BINDING_RAW, gpu::SHADOWS_DENOISE_BINDING_NORMALS,
                         gpu::SHADOWS_DENOISE_BINDING_DEPTH,
                         gpu::SHADOWS_DENOISE_BINDING_PREVIOUS_DEPTH,
                         gpu::SHADOWS_DENOISE_BINDING_FLAGS, gpu::SHADOWS_DENOISE_BINDING_VELOCITY,
                         gpu::SHADOWS_DENOISE_BINDING_PREVIOUS})) {}

Shadows ShadowsDenoisePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                    const GBuffer& gbuffer, const RawShadows& raw) {
  graph::HistoryImage history =
      graph.createHistoryImage("shadows.visibility", {VK_FORMAT_R16G16_SFLOAT});
  const graph::HistoryImage depth = gbuffer.depth;
  graph.addPass("shadows-denoise", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(raw.visibility, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_RAW)
      .read(gbuffer.normals, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_NORMALS)
      .read(depth.current, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_DEPTH)
      .read(depth.previous, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_PREVIOUS_DEPTH)
      .read(gbuffer.flags, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_FLAGS)
      .read(gbuffer.velocity, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_VELOCITY)
      .read(history.previous, Access::SampledRead, gpu::SHADOWS_DENOISE_BINDING_PREVIOUS)
      .write(history.current, Access::StorageWrite, gpu::SHADOWS_DENOISE_BINDING_CURRENT)
      .record([this, frame, history, depth](VkCommandBuffer cmd, const graph::PassResources& r) {
        // After a lighting cut the running mean would show the old shadows for up to
        // maxHistory frames: start afresh.
        bool valid = r.historyValid(history) && r.historyValid(depth) && !frame.lightingCut;
        pass_.record(cmd, r, frame.passConstants(valid), frame.resolution);
      });
  return {history.current};
}

}  // namespace bounce
