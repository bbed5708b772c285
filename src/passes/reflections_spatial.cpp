#include "passes/reflections_spatial.h"

#include "shared/restir_gi_io.h"

namespace bounce {

using graph::Access;

ReflectionsSpatialPass::ReflectionsSpatialPass(vk::Context& context, const GpuScene& gpuScene)
    : pass_(context, gpuScene, "passes/reflections_spatial", gpu::REFLECTIONS_SPATIAL_BINDING_COUNT,
            sizeof(gpu::ReflectionReuseConstants)) {}

ReflectionReservoirImages ReflectionsSpatialPass::declare(graph::FrameGraph& graph,
                                                          const FrameContext& frame,
                                                          const GBuffer& gbuffer,
                                                          const ReflectionReservoirImages& input,
                                                          const ReflectionReuseFrame& f) {
  ReflectionReservoirImages out = createReflectionReservoir(graph, "reflections.spatial", f.size);
  graph::PassBuilder pass = graph.addPass("reflections-spatial", graph::QueueKind::Compute);
  pass.read(frame.constants, Access::StorageRead);
  // The first image written is the pass's debug view: the chosen sample's radiance, M in alpha.
  pass.write(out[gpu::GI_RESERVOIR_RADIANCE], Access::StorageWrite,
             gpu::REFLECTIONS_SPATIAL_BINDING_OUTPUT + gpu::GI_RESERVOIR_RADIANCE);
  for (uint32_t i = 0; i < 4; ++i) {
    pass.read(input[i], Access::StorageRead, gpu::REFLECTIONS_SPATIAL_BINDING_INPUT + i);
    if (i != gpu::GI_RESERVOIR_RADIANCE)
      pass.write(out[i], Access::StorageWrite, gpu::REFLECTIONS_SPATIAL_BINDING_OUTPUT + i);
  }
  pass.read(gbuffer.normals, Access::StorageRead, gpu::REFLECTIONS_SPATIAL_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::REFLECTIONS_SPATIAL_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::StorageRead, gpu::REFLECTIONS_SPATIAL_BINDING_EMISSIVE)
      .record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
        recordReflectionReuse(pass_, cmd, r, f.constants, f.extent);
      });
  return out;
}

}  // namespace bounce
