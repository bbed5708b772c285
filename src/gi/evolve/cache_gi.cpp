#include "gi/evolve/cache_gi.h"

namespace bounce {

CacheGi::CacheGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                 const ClipmapCacheSettings& settings)
    : lights_(context, gpuScene, scene),
      cache_(context, gpuScene, lights_, settings),
      lookup_(context, gpuScene, "gi/evolve/gi_cache_lookup", gpu::CACHE_LOOKUP_IMAGES,
              sizeof(gpu::ClipmapPassConstants)) {}

DiffuseGiOutput CacheGi::declare(graph::FrameGraph& graph, const GiInputs& inputs) {
  using graph::Access;
  graph::ImageHandle output = createOutput(graph);
  cache_.declareUpdate(graph, inputs);
  gpu::ClipmapPassConstants push{};
  push.cache = cache_.constantsAddress();
  push.frame = inputs.frame.constantsAddress;
  VkExtent2D extent = inputs.frame.resolution;
  cache_.declareLookup(graph.addPass("gi-cache-lookup", graph::QueueKind::Compute))
      .read(inputs.frame.constants, Access::StorageRead)
      .read(inputs.gbuffer.normals, Access::StorageRead, gpu::CACHE_LOOKUP_BINDING_NORMALS)
      .read(inputs.gbuffer.depth.current, Access::StorageRead, gpu::CACHE_LOOKUP_BINDING_DEPTH)
      .read(inputs.gbuffer.flags, Access::StorageRead, gpu::CACHE_LOOKUP_BINDING_FLAGS)
      .write(output, Access::StorageWrite, gpu::CACHE_LOOKUP_BINDING_OUTPUT)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        lookup_.bind(cmd, push, r);
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  cache_.declareStatisticsReadback(graph);
  return {output};
}

}  // namespace bounce
