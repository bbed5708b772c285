#include "di/di_temporal.h"

#include "core/error.h"

namespace bounce {

using graph::Access;

DiTemporalPass::DiTemporalPass(vk::Context& context, const GpuScene& scene)
    : pass_(context, scene, "di/di_temporal", gpu::DI_TEMPORAL_BINDING_COUNT) {}

graph::ImageHandle DiTemporalPass::declare(graph::FrameGraph& graph, const DiFrame& f,
                                           graph::ImageHandle candidates) {
  if (!f.finalReservoirs) fail("di-temporal: declared without di.reservoir-final");
  const graph::HistoryImage history = *f.finalReservoirs;
  graph::ImageHandle reservoir = graph.createImage("di.reservoir", {kDiReservoirFormat});
  graph::HistoryImage surface =
      graph.createHistoryImage("di.reservoir-surface", {VK_FORMAT_R32G32B32A32_SFLOAT});
  graph::PassBuilder pass = graph.addPass("di-temporal", graph::QueueKind::Compute);
  readDiGBuffer(pass, f)
      .write(reservoir, Access::StorageWrite, gpu::DI_TEMPORAL_BINDING_CURRENT)
      .write(surface.current, Access::StorageWrite, gpu::DI_TEMPORAL_BINDING_CURRENT_SURFACE)
      .read(candidates, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_CANDIDATE)
      .read(f.gbuffer.velocity, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_VELOCITY)
      .read(history.previous, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_PREVIOUS)
      .read(surface.previous, Access::StorageRead, gpu::DI_TEMPORAL_BINDING_PREVIOUS_SURFACE)
      .record([this, f, history, surface](VkCommandBuffer cmd, const graph::PassResources& r) {
        // A lighting cut keeps the view's history but drops the light it holds; so does a
        // light switching on (RestirDi::setLights).
        const bool valid = !f.frame.lightingCut && !f.dropHistory && r.historyValid(history) &&
                           r.historyValid(surface);
        pass_.record(cmd, r, f.passConstants(valid), f.frame.resolution);
      });
  return reservoir;
}

}  // namespace bounce
