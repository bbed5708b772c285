#include "passes/shadows_trace.h"

namespace bounce {

using graph::Access;

ShadowsTracePass::ShadowsTracePass(vk::Context& context, const GpuScene& scene,
                                   const ShadowSettings& settings)
    : settings_(settings),
      pass_(context, scene, "passes/shadows_trace", gpu::SHADOWS_TRACE_BINDING_COUNT) {}

RawShadows ShadowsTracePass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                     const GBuffer& gbuffer) {
  RawShadows raw;
  raw.visibility = graph.createImage(
      "shadows.raw", {VK_FORMAT_R16G16_SFLOAT, graph::ImageSize::dividedRes(settings_.divisor)});
  const VkExtent2D extent = settings_.resolution(frame.resolution);
  graph.addPass("shadows-trace", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(frame.instances, Access::StorageRead)
      .read(frame.tlas, Access::StorageRead)
      .read(gbuffer.normals, Access::StorageRead, gpu::SHADOWS_TRACE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::SHADOWS_TRACE_BINDING_DEPTH)
      .read(gbuffer.flags, Access::StorageRead, gpu::SHADOWS_TRACE_BINDING_FLAGS)
      .write(raw.visibility, Access::StorageWrite, gpu::SHADOWS_TRACE_BINDING_RAW)
      .record([this, frame, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, frame.passConstants(), extent);
      });
  return raw;
}

}  // namespace bounce
