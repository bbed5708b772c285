#include "passes/reflections_resolve.h"

namespace bounce {

using graph::Access;

ReflectionsResolvePass::ReflectionsResolvePass(vk::Context& context, const GpuScene& gpuScene)
    : pass_(context, gpuScene, "passes/reflections_resolve", gpu::REFLECTIONS_RESOLVE_BINDING_COUNT,
            sizeof(gpu::ReflectionReuseConstants)) {}

graph::ImageHandle ReflectionsResolvePass::declare(graph::FrameGraph& graph,
                                                   const FrameContext& frame,
                                                   const GBuffer& gbuffer,
                                                   const ReflectionReservoirImages& reservoir,
                                                   graph::ImageHandle traced,
                                                   const ReflectionReuseFrame& f) {
  graph::ImageHandle resolved =
      graph.createImage("reflections.resolved", {VK_FORMAT_R16G16B16A16_SFLOAT, f.size});
  graph::PassBuilder pass = graph.addPass("reflections-resolve", graph::QueueKind::Compute);
  pass.read(frame.constants, Access::StorageRead)
      .write(resolved, Access::StorageWrite, gpu::REFLECTIONS_RESOLVE_BINDING_RESOLVED);
  for (uint32_t i = 0; i < 4; ++i)
    pass.read(reservoir[i], Access::StorageRead, gpu::REFLECTIONS_RESOLVE_BINDING_RESERVOIR + i);
  pass.read(gbuffer.normals, Access::StorageRead, gpu::REFLECTIONS_RESOLVE_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::REFLECTIONS_RESOLVE_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::StorageRead, gpu::REFLECTIONS_RESOLVE_BINDING_EMISSIVE)
      .read(traced, Access::StorageRead, gpu::REFLECTIONS_RESOLVE_BINDING_TRACED)
      .record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        recordReflectionReuse(pass_, cmd, r, f.constants, f.extent);
      });
  return resolved;
}

}  // namespace bounce
