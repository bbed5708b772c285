#include "passes/scene_update.h"

namespace bounce {

using graph::Access;

SceneUpdatePass::SceneUpdatePass(vk::Context& context, GpuScene& scene)
    : scene_(scene),
      constantsBuffer_(context, sizeof(gpu::FrameConstants),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       vk::MemoryUse::DeviceOnly, "frame-constants") {}

FrameContext SceneUpdatePass::declare(graph::FrameGraph& graph,
                                      const gpu::FrameConstants& constants, bool lightingCut) {
  FrameContext f;
  f.constants =
      graph.importBuffer("frame-constants", graph::ImportedBuffer::from(constantsBuffer_));
  f.constantsAddress = constantsBuffer_.address();
  f.hostConstants = &constants;
  f.instances =
      graph.importBuffer("scene.instances", graph::ImportedBuffer::from(scene_.instanceBuffer()));
  f.previousInstances = graph.importBuffer(
      "scene.previous-instances", graph::ImportedBuffer::from(scene_.previousInstanceBuffer()));
  f.tlas = graph.importBuffer("scene.tlas-nodes", graph::ImportedBuffer::from(scene_.tlasBuffer()));
  f.resolution = {constants.resolution.x, constants.resolution.y};
  f.lightingCut = lightingCut;
  const gpu::FrameConstants* host = &constants;
  graph.addPass("scene-update", graph::QueueKind::Compute)
      .write(f.constants, Access::TransferDst)
      .write(f.instances, Access::TransferDst)
      .write(f.previousInstances, Access::TransferDst)
      // Refitted by a compute shader, or copied from the CPU's rebuild (GpuScene::TlasUpdate).
      .write(f.tlas, scene_.tlasUpdate() == TlasUpdate::GpuRefit ? Access::StorageReadWrite
                                                                 : Access::TransferDst)
      .record([this, host, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        vkCmdUpdateBuffer(cmd, r.buffer(f.constants).buffer, 0, sizeof(*host), host);
        scene_.recordInstanceUpload(cmd);  // nothing when no instance moved
      });
  return f;
}

}  // namespace bounce
