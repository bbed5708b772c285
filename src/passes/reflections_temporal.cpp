#include "passes/reflections_temporal.h"

#include "shared/restir_gi_io.h"

namespace bounce {

using graph::Access;

namespace {

constexpr const char* kReservoirImageNames[4] = {"sample", "radiance", "origin", "normals"};

graph::ImageDesc reservoirImageDesc(uint32_t i, graph::ImageSize size) {
  return {i == gpu::GI_RESERVOIR_NORMALS ? VK_FORMAT_R16G16B16A16_SFLOAT
                                         : VK_FORMAT_R32G32B32A32_SFLOAT,
          size};
}

}  // namespace

ReflectionReservoirImages createReflectionReservoir(graph::FrameGraph& graph,
                                                    const std::string& prefix,
                                                    graph::ImageSize size) {
  ReflectionReservoirImages images;
  for (uint32_t i = 0; i < 4; ++i)
    images[i] =
        graph.createImage(prefix + "." + kReservoirImageNames[i], reservoirImageDesc(i, size));
  return images;
}

void recordReflectionReuse(ComputePass& pass, VkCommandBuffer cmd,
                           const graph::PassResources& resources,
                           const gpu::ReflectionReuseConstants& constants, VkExtent2D extent) {
  pass.bind(cmd, constants, resources);
  vk::ComputePipeline::dispatchCovering(cmd, extent.width, extent.height, gpu::HYBRID_GROUP_SIZE,
                                        gpu::HYBRID_GROUP_SIZE);
}

ReflectionsTemporalPass::ReflectionsTemporalPass(vk::Context& context, const GpuScene& gpuScene)
    : pass_(context, gpuScene, "passes/reflections_temporal",
            gpu::REFLECTIONS_TEMPORAL_BINDING_COUNT, sizeof(gpu::ReflectionReuseConstants)) {}

ReflectionReservoirImages ReflectionsTemporalPass::declare(
    graph::FrameGraph& graph, const FrameContext& frame, const GBuffer& gbuffer,
    const ReflectionReservoirImages& candidate, const ReflectionReuseFrame& f) {
  std::array<graph::HistoryImage, 4> history;
  for (uint32_t i = 0; i < 4; ++i)
    history[i] =
        graph.createHistoryImage(std::string("reflections.reservoir.") + kReservoirImageNames[i],
                                 reservoirImageDesc(i, f.size));
  graph::HistoryImage lobe =
      graph.createHistoryImage("reflections.reservoir.lobe", {VK_FORMAT_R32G32_SFLOAT, f.size});
  graph::PassBuilder pass = graph.addPass("reflections-temporal", graph::QueueKind::Compute);
  pass.read(frame.constants, Access::StorageRead);
  // The first image written is the pass's debug view: the chosen sample's radiance, M in alpha.
  pass.write(history[gpu::GI_RESERVOIR_RADIANCE].current, Access::StorageWrite,
             gpu::REFLECTIONS_TEMPORAL_BINDING_CURRENT + gpu::GI_RESERVOIR_RADIANCE);
  for (uint32_t i = 0; i < 4; ++i) {
    pass.read(candidate[i], Access::StorageRead, gpu::REFLECTIONS_TEMPORAL_BINDING_CANDIDATE + i)
        .read(history[i].previous, Access::StorageRead,
              gpu::REFLECTIONS_TEMPORAL_BINDING_PREVIOUS + i);
    if (i != gpu::GI_RESERVOIR_RADIANCE)
      pass.write(history[i].current, Access::StorageWrite,
                 gpu::REFLECTIONS_TEMPORAL_BINDING_CURRENT + i);
  }
  pass.read(gbuffer.normals, Access::StorageRead, gpu::REFLECTIONS_TEMPORAL_BINDING_NORMALS)
      .read(gbuffer.depth.current, Access::StorageRead, gpu::REFLECTIONS_TEMPORAL_BINDING_DEPTH)
      .read(gbuffer.emissive, Access::StorageRead, gpu::REFLECTIONS_TEMPORAL_BINDING_EMISSIVE)
      .read(gbuffer.velocity, Access::StorageRead, gpu::REFLECTIONS_TEMPORAL_BINDING_VELOCITY)
      .read(lobe.previous, Access::StorageRead, gpu::REFLECTIONS_TEMPORAL_BINDING_PREVIOUS_LOBE)
      .write(lobe.current, Access::StorageWrite, gpu::REFLECTIONS_TEMPORAL_BINDING_CURRENT_LOBE);
  const bool lightingCut = frame.lightingCut;
  pass.record(
      [this, f, history, lobe, lightingCut](VkCommandBuffer cmd, const graph::PassResources& r) {
        // No history in the first frame, after a reset or resize (the graph's), or after a lighting
        // cut (the stored radiance is the old light's).
        bool valid = !lightingCut && r.historyValid(lobe);
        for (const graph::HistoryImage& image : history) valid = valid && r.historyValid(image);
        gpu::ReflectionReuseConstants c = f.constants;
        c.historyValid = valid ? 1u : 0u;
        recordReflectionReuse(pass_, cmd, r, c, f.extent);
      });
  return {history[0].current, history[1].current, history[2].current, history[3].current};
}

}  // namespace bounce
