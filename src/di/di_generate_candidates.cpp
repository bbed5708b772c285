#include "di/di_generate_candidates.h"

namespace bounce {

namespace {

std::array<uint32_t, 1> brdfSpecialization(bool brdfCandidate) {
  return {brdfCandidate ? 1u : 0u};
}

}  // namespace

DiGenerateCandidatesPass::DiGenerateCandidatesPass(vk::Context& context, const GpuScene& scene,
                                                   bool brdfCandidate, bool visibility)
    : generate_(context, scene, "di/di_generate_candidates", gpu::DI_CANDIDATES_BINDING_COUNT,
                brdfSpecialization(brdfCandidate)) {
  if (visibility)
    visibility_.emplace(context, scene, "di/di_trace_candidate_visibility",
                        gpu::DI_CANDIDATES_BINDING_COUNT);
}

graph::ImageHandle DiGenerateCandidatesPass::declare(graph::FrameGraph& graph, const DiFrame& f) {
  graph::ImageHandle candidates = graph.createImage("di.candidate", {kDiReservoirFormat});
  graph::PassBuilder pass = graph.addPass("di-generate-candidates", graph::QueueKind::Compute);
  readDiGBuffer(pass, f).write(candidates, graph::Access::StorageWrite,
                               gpu::DI_CANDIDATES_BINDING_RESERVOIR);
  if (f.lightGrid) pass.read(*f.lightGrid, graph::Access::StorageRead);
  pass.record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
    generate_.record(cmd, r, f.passConstants(), f.frame.resolution);
  });
  if (!visibility_) return candidates;
  graph::PassBuilder trace =
      graph.addPass("di-trace-candidate-visibility", graph::QueueKind::Compute);
  readDiGBuffer(trace, f).write(candidates, graph::Access::StorageReadWrite,
                                gpu::DI_CANDIDATES_BINDING_RESERVOIR);
  trace.record([this, f](VkCommandBuffer cmd, const graph::PassResources& r) {
    visibility_->record(cmd, r, f.passConstants(), f.frame.resolution,
                        gpu::DI_VISIBILITY_GROUP_SIDE);
  });
  return candidates;
}

}  // namespace bounce
