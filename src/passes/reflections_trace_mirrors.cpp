#include "passes/reflections_trace_mirrors.h"

namespace bounce {

using graph::Access;

ReflectionsTraceMirrorsPass::ReflectionsTraceMirrorsPass(vk::Context& context,
                                                         const GpuScene& gpuScene)
    : pass_(context, gpuScene, "passes/reflections_trace_mirrors",
            gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_COUNT, sizeof(gpu::ReflectionPassConstants)) {}

void ReflectionsTraceMirrorsPass::declare(graph::FrameGraph& graph, const FrameContext& frame,
                                          const GBuffer& gbuffer, const RadianceCacheLookup& cache,
                                          const gpu::ReflectionPassConstants& constants,
                                          const TracedReflections& traced,
                                          const Reflections& reflections) {
  const VkExtent2D extent = frame.resolution;
  graph::PassBuilder added = graph.addPass("reflections-trace-mirrors", graph::QueueKind::Compute);
  graph::PassBuilder pass = constants.cache != 0 ? cache.declare(added) : added;
  pass.read(frame.constants, Access::StorageRead)
      .read(frame.instances, Access::StorageRead)
      .read(frame.tlas, Access::StorageRead)
      .read(gbuffer.normals, Access::StorageRead, gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead,
            gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::StorageRead, gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_EMISSIVE)
      .read(gbuffer.flags, Access::StorageRead, gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_FLAGS)
      .read(traced.traced, Access::StorageRead, gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_TRACED)
      .write(reflections.radiance, Access::StorageReadWrite,
             gpu::REFLECTIONS_TRACE_MIRRORS_BINDING_REFLECTIONS)
      .record([this, constants, extent](VkCommandBuffer cmd, const graph::PassResources& r) {
        pass_.bind(cmd, constants, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
}

}  // namespace bounce
