#include "di/di_generate_candidates.h"

namespace bounce {

DiGenerateCandidatesPass::DiGenerateCandidatesPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "di/di_generate_candidates", gpu::DI_CANDIDATES_BINDING_COUNT) {}

graph::ImageHandle DiGenerateCandidatesPass::declare(graph::FrameGraph& graph, const DiFrame& f) {
  graph::ImageHandle candidates = graph.createImage("di.candidate", {kDiReservoirFormat});
  graph::PassBuilder pass = graph.addPass("di-generate-candidates", graph::QueueKind::Compute);
  readDiGBuffer(pass, f).write(candidates, graph::Access::StorageWrite,
                               gpu::DI_CANDIDATES_BINDING_RESERVOIR);
  if (f.lightGrid) pass.read(*f.lightGrid, graph::Access::StorageRead);
  pass.record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
    pass_.record(cmd, r, f.passConstants(), f.frame.resolution);
  });
  return candidates;
}

}  // namespace bounce
