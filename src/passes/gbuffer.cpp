#include "passes/gbuffer.h"

namespace bounce {

using graph::Access;

GBuffer GBuffer::create(graph::FrameGraph& graph) {
  constexpr VkFormat rgba16f = VK_FORMAT_R16G16B16A16_SFLOAT;
  GBuffer g;
  g.baseColor = graph.createImage("gbuffer.base-color", {rgba16f});
  g.normals = graph.createImage("gbuffer.normals", {rgba16f});
  g.depth = graph.createHistoryImage("gbuffer.depth", {VK_FORMAT_R32_SFLOAT});
  g.uv = graph.createImage("gbuffer.uv", {VK_FORMAT_R32G32_SFLOAT});
  g.velocity = graph.createImage("gbuffer.velocity", {VK_FORMAT_R16G16_SFLOAT});
  g.emissive = graph.createImage("gbuffer.emissive", {rgba16f});
  g.flags = graph.createImage("gbuffer.flags", {VK_FORMAT_R32_UINT});
  return g;
}

GBufferPass::GBufferPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "passes/gbuffer", gpu::GBUFFER_BINDING_COUNT) {}

GBuffer GBufferPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                             const VBuffer& vbuffer) {
  GBuffer g = GBuffer::create(graph);
  graph.addPass("gbuffer", graph::QueueKind::Compute)
      .read(frame.constants, Access::StorageRead)
      .read(frame.instances, Access::StorageRead)
      .read(frame.previousInstances, Access::StorageRead)
      .read(vbuffer.ids, Access::StorageRead, gpu::GBUFFER_BINDING_IDS)
      .write(g.baseColor, Access::StorageWrite, gpu::GBUFFER_BINDING_BASE_COLOR)
      .write(g.normals, Access::StorageWrite, gpu::GBUFFER_BINDING_NORMALS)
      .write(g.depth.current, Access::StorageWrite, gpu::GBUFFER_BINDING_DEPTH)
      .write(g.uv, Access::StorageWrite, gpu::GBUFFER_BINDING_UV)
      .write(g.velocity, Access::StorageWrite, gpu::GBUFFER_BINDING_VELOCITY)
      .write(g.emissive, Access::StorageWrite, gpu::GBUFFER_BINDING_EMISSIVE)
      .write(g.flags, Access::StorageWrite, gpu::GBUFFER_BINDING_FLAGS)
      .record([this, frame](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.record(cmd, r, frame.passConstants(), frame.resolution);
      });
  return g;
}

}  // namespace bounce
