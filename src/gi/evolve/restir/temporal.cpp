#include "gi/evolve/restir/temporal.h"

namespace bounce {

using graph::Access;

TemporalStage::TemporalStage(vk::Context& context, const GpuScene& scene)
    : temporal_(context, scene, "gi/evolve/restir/gi_restir_temporal",
                gpu::GI_TEMPORAL_BINDING_COUNT) {}

Reservoirs TemporalStage::declare(graph::FrameGraph& graph, const RestirFrame& f,
                                  const Candidates& candidates, const ReservoirHistory& history,
                                  const std::optional<graph::HistoryImage>& occlusionValidity) {
  Reservoirs out;
  out.estimate =
      graph.createImage("gi.reservoir-estimate", {VK_FORMAT_R16G16B16A16_SFLOAT, f.giSize});
  for (int i = 0; i < 4; ++i) out.reservoir[i] = history[i].current;
  // The running mean of each neighbourhood's candidates and whether they were brighter than it
  // last frame (RestirGiSettings::historyBrightening).
  graph::HistoryImage candidateMean =
      graph.createHistoryImage("gi.candidate-mean", {VK_FORMAT_R32G32_SFLOAT, f.giSize});
  const GBuffer& g = f.in.gbuffer;
  graph::PassBuilder pass = graph.addPass("gi-restir-temporal", graph::QueueKind::Compute);
  pass.read(f.in.frame.constants, Access::StorageRead)
      .read(g.normals, Access::StorageRead, gpu::GI_TEMPORAL_BINDING_NORMALS)
      .read(g.depth.current, Access::StorageRead, gpu::GI_TEMPORAL_BINDING_DEPTH)
      .read(g.velocity, Access::StorageRead, gpu::GI_TEMPORAL_BINDING_VELOCITY);
  // The first image written is the reservoir's estimate: the pass's debug view.
  pass.write(out.estimate, Access::StorageWrite, gpu::GI_TEMPORAL_BINDING_ESTIMATE);
  for (uint32_t i = 0; i < 4; ++i)
    pass.read(candidates.reservoir[i], Access::StorageRead, gpu::GI_TEMPORAL_BINDING_CANDIDATE + i)
        .read(history[i].previous, Access::StorageRead, gpu::GI_TEMPORAL_BINDING_PREVIOUS + i)
        .write(history[i].current, Access::StorageWrite, gpu::GI_TEMPORAL_BINDING_CURRENT + i);
  pass.read(candidates.validity, Access::StorageRead, gpu::GI_TEMPORAL_BINDING_VALIDITY)
      .read(candidates.estimate, Access::StorageRead, gpu::GI_TEMPORAL_BINDING_CANDIDATE_ESTIMATE)
      .read(candidateMean.previous, Access::StorageRead,
            gpu::GI_TEMPORAL_BINDING_PREVIOUS_CANDIDATE_MEAN)
      .write(candidateMean.current, Access::StorageWrite,
             gpu::GI_TEMPORAL_BINDING_CURRENT_CANDIDATE_MEAN);
  if (occlusionValidity)
    pass.read(occlusionValidity->previous, Access::StorageRead,
              gpu::GI_TEMPORAL_BINDING_OCCLUSION_VALIDITY);
  else  // the shader ignores the binding without the validation pass
    pass.readPlaceholder(candidates.neeVisibility, gpu::GI_TEMPORAL_BINDING_OCCLUSION_VALIDITY);
  pass.record(
      [this, f, history, candidateMean](VkCommandBuffer cmd, const graph::PassResources& r) {
        bool valid = !f.lightCutPending && r.historyValid(candidateMean);
        for (const graph::HistoryImage& image : history) valid = valid && r.historyValid(image);
        temporal_.record(cmd, r, f.passConstants(valid), f.giResolution);
      });
  return out;
}

}  // namespace bounce
