#include "di/di_temporal.h"

#include <vector>

#include "core/error.h"

namespace bounce {

using graph::Access;

namespace {

// di-candidates-temporal's specialization, DI_SPEC_BRDF_CANDIDATE; none for di-temporal.
std::vector<uint32_t> temporalSpecialization(bool drawsCandidates, bool brdfCandidate) {
  if (!drawsCandidates) return {};
  return {brdfCandidate ? 1u : 0u};
}

}  // namespace

DiTemporalPass::DiTemporalPass(vk::Context& context, const GpuScene& scene, bool drawsCandidates,
                               bool brdfCandidate)
    : drawsCandidates_(drawsCandidates),
      pass_(context, scene, drawsCandidates ? "di/di_candidates_temporal" : "di/di_temporal",
            drawsCandidates ? gpu::DI_CANDIDATES_TEMPORAL_BINDING_COUNT
                            : gpu::DI_TEMPORAL_BINDING_COUNT,
            temporalSpecialization(drawsCandidates, brdfCandidate)) {}

graph::ImageHandle DiTemporalPass::declare(graph::FrameGraph& graph, const DiFrame& f,
                                           std::optional<graph::ImageHandle> candidates) {
  if (!f.finalReservoirs) fail("di-temporal: declared without di.reservoir-final");
  if (drawsCandidates_ == candidates.has_value())
    fail("di-temporal: {}", drawsCandidates_ ? "draws its own candidates, given di.candidate"
                                             : "declared without di.candidate");
  const graph::HistoryImage history = *f.finalReservoirs;
  graph::ImageHandle reservoir = graph.createImage("di.reservoir", {kDiReservoirFormat});
  graph::HistoryImage surface =
      graph.createHistoryImage("di.reservoir-surface", {VK_FORMAT_R32G32B32A32_SFLOAT});
  graph::PassBuilder pass = graph.addPass(
      drawsCandidates_ ? "di-candidates-temporal" : "di-temporal", graph::QueueKind::Compute);
  readDiGBuffer(pass, f)
      .write(reservoir, Access::StorageWrite, gpu::DI_TEMPORAL_BINDING_CURRENT)
      .write(surface.current, Access::StorageWrite, gpu::DI_TEMPORAL_BINDING_CURRENT_SURFACE)
      .read(f.gbuffer.velocity, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_VELOCITY)
      .read(history.previous, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_PREVIOUS)
      .read(surface.previous, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_PREVIOUS_SURFACE);
  if (candidates) pass.read(*candidates, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_CANDIDATE);
  if (drawsCandidates_ && f.lightGrid) pass.read(*f.lightGrid, Access::StorageRead);
  pass.record([this, f, history, surface](VkCommandBuffer cmd, const graph::PassResources& r) {
    // A lighting cut keeps the view's history but drops the light it holds; so does a light
    // switching on (RestirDi::setLights).
    const bool valid = !f.frame.lightingCut && !f.dropHistory && r.historyValid(history) &&
                       r.historyValid(surface);
    pass_.record(cmd, r, f.passConstants(valid), f.frame.resolution);
  });
  return reservoir;
}

}  // namespace bounce
