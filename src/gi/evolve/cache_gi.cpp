#include "gi/evolve/cache_gi.h"

namespace bounce {

CacheGi::CacheGi(vk::Context& context, GpuScene& gpuScene, const Scene& scene,
                 const HybridSettings& settings)
    : lights_(context, gpuScene, scene),
      cache_(context, gpuScene, lights_, settings.cache),
      lookup_(context, gpuScene, "gi/evolve/gi_cache_lookup", gpu::CACHE_LOOKUP_IMAGES,
              sizeof(gpu::ClipmapPassConstants)) {}

void CacheGi::declare(graph::FrameGraph& graph, const FrameInputs& inputs,
                      graph::ImageHandle output) {
  using graph::Access;
  cache_.declareUpdate(graph, inputs);
  gpu::ClipmapPassConstants push{};
  push.cache = cache_.constantsAddress();
  push.frame = inputs.frameConstantsAddress;
  VkExtent2D extent = inputs.resolution;
  cache_.declareLookup(graph.addPass("gi-cache-lookup", graph::QueueKind::Compute))
      .read(inputs.frameConstants, Access::StorageRead)
      .read(inputs.normals, Access::StorageRead)
      .read(inputs.depth.current, Access::StorageRead)
      .read(inputs.flags, Access::StorageRead)
      .write(output, Access::StorageWrite)
      .record([=, this](VkCommandBuffer cmd, const graph::PassResources& r) {
        lookup_.bind(cmd, push,
                     {{gpu::CACHE_LOOKUP_BINDING_NORMALS, r.image(inputs.normals)},
                      {gpu::CACHE_LOOKUP_BINDING_DEPTH, r.image(inputs.depth.current)},
                      {gpu::CACHE_LOOKUP_BINDING_FLAGS, r.image(inputs.flags)},
                      {gpu::CACHE_LOOKUP_BINDING_OUTPUT, r.image(output)}});
        vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height,
                                              gpu::HYBRID_GROUP_SIZE, gpu::HYBRID_GROUP_SIZE);
      });
  cache_.declareStatisticsReadback(graph);
}

}  // namespace bounce
